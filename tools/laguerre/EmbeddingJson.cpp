#include "EmbeddingJson.hpp"

#include <charconv>
#include <fstream>
#include <unordered_map>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/graph/GraphError.hpp"

namespace laguerre::tools {

using nlohmann::json;

void write_embedding_json(std::ostream& os, json doc, const core::PlanarGraph& g, const core::CircleEmbedding& circles,
                          const std::vector<std::string>& local) {
  json outer = json::array();
  for (core::Vertex v : g.boundary_cycle()) outer.push_back(g.id(v));
  doc["outer_face"] = std::move(outer);
  LAGUERRE_PRECONDITION(doc.is_object() && !doc.contains("vertices") && (--doc.end()).key() < "vertices",
                        "write_embedding_json: every key of the document must sort before \"vertices\".");
  LAGUERRE_PRECONDITION(local.empty() || local.size() == g.num_vertices(), "write_embedding_json: one 'local' per vertex.");
  // dump(1) of the keys before "vertices", its closing "\n}" removed; then the vertices at depth 2,
  // with dump(1)'s layout: one space of indent per level, "key": value, ",\n" between members.
  std::string text = doc.dump(1);
  text.resize(text.size() - 2);
  text += ",\n \"vertices\": ";
  if (g.num_vertices() == 0) text += "[]";
  const auto number = [&](double x) { text += json(x).dump(); };  // nlohmann's own number format
  const auto integer = [&](std::uint64_t x) {
    char buf[24];
    text.append(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  };
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    text += v == 0 ? "[\n  {\n   \"boundary\": " : ",\n  {\n   \"boundary\": ";
    text += g.is_boundary(v) ? "true" : "false";
    text += ",\n   \"id\": ";
    integer(g.id(v));
    if (!local.empty()) {
      text += ",\n   \"local\": ";
      text += json(local[v]).dump();
    }
    text += ",\n   \"neighbours\": ";
    const auto nb = g.neighbours(v);
    if (nb.empty()) text += "[]";
    for (std::size_t i = 0; i < nb.size(); ++i) {
      text += i == 0 ? "[\n    " : ",\n    ";
      integer(g.id(nb[i]));
    }
    if (!nb.empty()) text += "\n   ]";
    text += ",\n   \"r\": ";
    number(circles[v].r);
    text += ",\n   \"x\": ";
    number(circles[v].x);
    text += ",\n   \"y\": ";
    number(circles[v].y);
    text += "\n  }";
    if (text.size() >= (1u << 20)) {  // written in pieces of about a megabyte
      os << text;
      text.clear();
    }
  }
  if (g.num_vertices() > 0) text += "\n ]";
  text += "\n}";
  os << text;
}

bool is_embedding_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return false;
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  if (c != '{') return false;
  in.seekg(0);
  try {
    const json doc = json::parse(in);
    return doc.value("format", "") == "laguerre-embedding";
  } catch (const json::exception&) {
    return false;
  }
}

EmbeddedGraph read_embedding(const std::string& path) {
  std::ifstream in = core::open_input_file(path, "embedding file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    throw core::GraphInputError(path, 0, 0, std::string("not valid JSON: ") + e.what());
  }
  auto need = [&](const json& obj, const char* key, const std::string& where) -> const json& {
    if (!obj.is_object() || !obj.contains(key))
      throw core::GraphInputError(path, 0, 0, "missing key '" + where + key + "'");
    return obj.at(key);
  };
  try {
    const json& vs = need(doc, "vertices", "");
    if (!vs.is_array() || vs.empty()) throw core::GraphInputError(path, 0, 0, "'vertices' must be a non-empty array");
    std::unordered_map<std::uint64_t, core::Vertex> index;
    std::vector<std::uint64_t> ids;
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const auto id = need(vs[i], "id", "vertices[" + std::to_string(i) + "].").get<std::uint64_t>();
      if (!index.emplace(id, static_cast<core::Vertex>(i)).second)
        throw core::GraphInputError(path, 0, 0, "vertex id " + std::to_string(id) + " appears twice in 'vertices'");
      ids.push_back(id);
    }
    std::vector<std::vector<core::Vertex>> rotation(vs.size());
    core::CircleEmbedding circles(vs.size());
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const std::string where = "vertices[" + std::to_string(i) + "].";
      circles[i] = {need(vs[i], "x", where).get<double>(), need(vs[i], "y", where).get<double>(),
                    need(vs[i], "r", where).get<double>()};
      for (const json& w : need(vs[i], "neighbours", where)) {
        auto it = index.find(w.get<std::uint64_t>());
        if (it == index.end())
          throw core::GraphInputError(path, 0, 0, "'" + where + "neighbours' names unknown vertex " + w.dump());
        rotation[i].push_back(it->second);
      }
    }
    core::PlanarGraph g;
    try {
      g = core::PlanarGraph::from_rotation(rotation, ids);
    } catch (const core::InputError& e) {
      throw core::GraphInputError(path, 0, 0, std::string("the rotation system is invalid: ") + e.what());
    }
    const json& outer = need(doc, "outer_face", "");
    if (outer.size() < 2) throw core::GraphInputError(path, 0, 0, "'outer_face' must list at least two vertices");
    const core::Vertex a = index.at(outer[0].get<std::uint64_t>()), b = index.at(outer[1].get<std::uint64_t>());
    const core::Dart d = g.find_dart(a, b);
    if (d == core::none) throw core::GraphInputError(path, 0, 0, "'outer_face' does not follow an edge of the graph");
    return {g.with_outer_dart(d), circles, doc.value("name", path)};
  } catch (const json::exception& e) {
    throw core::GraphInputError(path, 0, 0, std::string("unexpected JSON content: ") + e.what());
  } catch (const std::out_of_range&) {
    throw core::GraphInputError(path, 0, 0, "'outer_face' names an unknown vertex");
  }
}

}  // namespace laguerre::tools
