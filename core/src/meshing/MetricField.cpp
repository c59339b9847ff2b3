#include "laguerre/core/meshing/MetricField.hpp"

#include "laguerre/core/meshing/Medit.hpp"

#include <muParser.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

namespace laguerre::core {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

/// `m`, the value of `field` at (x, y), if it is a metric; otherwise a FieldError naming the field.
Metric checked(const Metric& m, double x, double y, const MetricField& field) {
  if (!is_metric(m))
    throw FieldError("metric field '" + field.describe() + "': the matrix [[" + number(m.a) + ", " + number(m.b) +
                     "], [" + number(m.b) + ", " + number(m.c) + "]] at (" + number(x) + ", " + number(y) + ") is not symmetric positive definite");
  return m;
}

/// The shortest decimal form that reads back (strtod, muparser) as the same double.
std::string exact_number(double v) {
  char text[32];
  return {text, std::to_chars(text, text + sizeof text, v).ptr};
}

/// A constant field. It describes itself by the specification that reads back to the same matrix bit
/// for bit: the sizes it was parsed from (sizes recomputed from the matrix need not, and for extreme
/// anisotropy may not even give an SPD matrix), or else its entries.
class UniformField final : public MetricField {
public:
  UniformField(const Metric& m, std::string description) : m_(m), description_(std::move(description)) {
    if (!is_metric(m)) throw FieldError("uniform field: the matrix is not symmetric positive definite");
  }
  explicit UniformField(const Metric& m)
      : UniformField(m, "expr:a=" + exact_number(m.a) + ";b=" + exact_number(m.b) + ";c=" + exact_number(m.c)) {}
  Metric at(double, double) const override { return m_; }
  std::string describe() const override { return description_; }

private:
  Metric m_;
  std::string description_;
};

class ShockLayerField final : public MetricField {
public:
  ShockLayerField(double h_min, double h_max, double width, double x0)
      : h_min_(h_min), h_max_(h_max), width_(width), x0_(x0) {
    if (!(h_min > 0) || !(h_max >= h_min) || !(width > 0) || !std::isfinite(h_max) || !std::isfinite(x0))
      throw FieldError("shock field: expected 0 < HMIN <= HMAX, WIDTH > 0 and a finite X0");
  }
  Metric at(double x, double y) const override {
    const double across = h_min_ + (h_max_ - h_min_) * (1 - std::exp(-std::abs(x - x0_) / width_));
    return checked({1 / (across * across), 0, 1 / (h_max_ * h_max_)}, x, y, *this);
  }
  std::string describe() const override {
    return "shock:" + number(h_min_) + ":" + number(h_max_) + ":" + number(width_) + ":" + number(x0_);
  }

private:
  double h_min_, h_max_, width_, x0_;
};

class ThesisField final : public MetricField {
public:
  ThesisField(double h, double ratio, double width, double y0) : h_(h), ratio_(ratio), width_(width), y0_(y0) {
    if (!(h > 0) || !(ratio >= 1) || !(width > 0) || !std::isfinite(h) || !std::isfinite(ratio) || !std::isfinite(y0))
      throw FieldError("thesis field: expected H > 0, RATIO >= 1, WIDTH > 0 and a finite Y0");
  }
  Metric at(double x, double y) const override {
    // s = +1 above the band (long horizontally), −1 below (long vertically), linear in between; the
    // sizes are h·RATIO^{±s/2}, so log-sizes are continuous and piecewise linear in y.
    const double s = std::clamp((y - y0_) / width_, -1.0, 1.0);
    const double hx = h_ * std::pow(ratio_, 0.5 * s), hy = h_ * std::pow(ratio_, -0.5 * s);
    return checked({1 / (hx * hx), 0, 1 / (hy * hy)}, x, y, *this);
  }
  std::string describe() const override {
    return "thesis:" + number(h_) + ":" + number(ratio_) + ":" + number(width_) + ":" + number(y0_);
  }

private:
  double h_, ratio_, width_, y0_;
};

/// muparser expressions in x, y (and z), evaluated together: the entries or sizes of 2D and 3D fields.
class Expressions {
public:
  Expressions(const std::string& spec, const std::vector<std::string>& names,
              const std::map<std::string, std::string>& exprs)
      : spec_(spec), parsers_(names.size()) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      mu::Parser& p = parsers_[i];
      p.DefineVar("x", &x_);
      p.DefineVar("y", &y_);
      p.DefineVar("z", &z_);
      p.DefineConst("pi", M_PI);
      try {
        p.SetExpr(exprs.at(names[i]));
        x_ = 0.5, y_ = 0.5, z_ = 0.5;
        p.Eval();  // compiles now, so syntax errors surface at parse time
      } catch (const mu::Parser::exception_type& e) {
        throw FieldError("metric field '" + spec_ + "': in " + names[i] + "=" + exprs.at(names[i]) + ": " + e.GetMsg());
      }
    }
  }
  /// The values of the expressions at (x, y, z), in the order of `names`.
  template <std::size_t N>
  std::array<double, N> at(double x, double y, double z) const {
    std::array<double, N> v{};
    // muparser evaluates through the bound variables: one evaluation at a time.
    const std::lock_guard lock(mutex_);
    x_ = x, y_ = y, z_ = z;
    try {
      for (std::size_t i = 0; i < N; ++i) v[i] = parsers_[i].Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw FieldError("metric field '" + spec_ + "': " + e.GetMsg());
    }
    return v;
  }

private:
  std::string spec_;
  mutable std::mutex mutex_;
  mutable double x_ = 0, y_ = 0, z_ = 0;
  mutable std::vector<mu::Parser> parsers_;
};

/// Three muparser expressions in x and y, giving either (a, b, c) or (h1, h2, θ).
class ExpressionField final : public MetricField {
public:
  ExpressionField(std::string spec, const std::vector<std::string>& names, std::map<std::string, std::string> exprs,
                  bool sizes)
      : spec_(std::move(spec)), sizes_(sizes), expressions_(spec_, names, exprs) {}
  Metric at(double x, double y) const override {
    const auto v = expressions_.at<3>(x, y, 0);
    if (sizes_) {
      if (!(v[0] > 0) || !(v[1] > 0) || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw FieldError("metric field '" + spec_ + "': sizes h1=" + number(v[0]) + ", h2=" + number(v[1]) +
                         " at (" + number(x) + ", " + number(y) + ") are not positive and finite");
      // Positive finite sizes can still give a matrix the doubles cannot hold (sizes below about
      // 1e-154 or above 1e154, or an extreme ratio): checked like the entries of expr fields.
      return checked(metric_from_sizes(v[0], v[1], v[2]), x, y, *this);
    }
    return checked({v[0], v[1], v[2]}, x, y, *this);
  }
  std::string describe() const override { return spec_; }

private:
  std::string spec_;
  bool sizes_;
  Expressions expressions_;
};

/// Per-vertex metrics on a triangle mesh, interpolated linearly (barycentric) inside each triangle.
/// Triangles are bucketed in a uniform grid of about one triangle per cell.
class BackgroundMeshField final : public MetricField {
public:
  BackgroundMeshField(std::string spec, TriangleMesh mesh, std::vector<Metric> metrics)
      : spec_(std::move(spec)), mesh_(std::move(mesh)), metrics_(std::move(metrics)) {
    if (mesh_.triangles.empty()) throw FieldError("metric field '" + spec_ + "': the background mesh has no triangles");
    lo_ = hi_ = mesh_.points[mesh_.triangles[0][0]];
    for (const auto& t : mesh_.triangles)
      for (std::size_t v : t)
        for (int k = 0; k < 2; ++k) {
          lo_[k] = std::min(lo_[k], mesh_.points[v][k]);
          hi_[k] = std::max(hi_[k], mesh_.points[v][k]);
        }
    const double side = std::sqrt(static_cast<double>(mesh_.triangles.size()));
    nx_ = ny_ = std::max<std::size_t>(1, static_cast<std::size_t>(side));
    cells_.resize(nx_ * ny_);
    for (std::size_t i = 0; i < mesh_.triangles.size(); ++i) {
      std::array<double, 2> a = mesh_.points[mesh_.triangles[i][0]], b = a;
      for (std::size_t v : mesh_.triangles[i])
        for (int k = 0; k < 2; ++k) {
          a[k] = std::min(a[k], mesh_.points[v][k]);
          b[k] = std::max(b[k], mesh_.points[v][k]);
        }
      const auto [i0, j0] = cell(a[0], a[1]);
      const auto [i1, j1] = cell(b[0], b[1]);
      for (std::size_t j = j0; j <= j1; ++j)
        for (std::size_t k = i0; k <= i1; ++k) cells_[j * nx_ + k].push_back(i);
    }
    tolerance_ = 1e-9 * std::max(hi_[0] - lo_[0], hi_[1] - lo_[1]);
  }

  Metric at(double x, double y) const override {
    const auto [ci, cj] = cell(x, y);
    const bool inside_box = x >= lo_[0] - tolerance_ && x <= hi_[0] + tolerance_ && y >= lo_[1] - tolerance_ &&
                            y <= hi_[1] + tolerance_;
    if (inside_box)
      for (std::size_t t : cells_[cj * nx_ + ci]) {
        const auto w = barycentric(t, x, y);
        if (std::min({w[0], w[1], w[2]}) >= -1e-12) return interpolate(t, w);
      }
    // Points on the boundary may miss every triangle by rounding: accept the nearest triangle within
    // the tolerance (relative 1e-9 of the mesh's extent), otherwise the point is outside the mesh.
    double best = tolerance_;
    std::size_t found = mesh_.triangles.size();
    if (inside_box)
      for (std::size_t t = 0; t < mesh_.triangles.size(); ++t)
        if (const double d = distance_to(t, x, y); d <= best) best = d, found = t;
    if (found == mesh_.triangles.size())
      throw FieldError("metric field '" + spec_ + "': the point (" + number(x) + ", " + number(y) +
                       ") is outside the background mesh");
    auto w = barycentric(found, x, y);
    for (double& c : w) c = std::max(c, 0.0);
    const double sum = w[0] + w[1] + w[2];
    for (double& c : w) c /= sum;
    return interpolate(found, w);
  }
  std::string describe() const override { return spec_; }

private:
  std::pair<std::size_t, std::size_t> cell(double x, double y) const {
    auto index = [](double v, double lo, double hi, std::size_t n) {
      const double t = hi > lo ? (v - lo) / (hi - lo) : 0;
      return static_cast<std::size_t>(std::clamp(t * static_cast<double>(n), 0.0, static_cast<double>(n - 1)));
    };
    return {index(x, lo_[0], hi_[0], nx_), index(y, lo_[1], hi_[1], ny_)};
  }
  std::array<double, 3> barycentric(std::size_t t, double x, double y) const {
    const auto& p = mesh_.points[mesh_.triangles[t][0]];
    const auto& q = mesh_.points[mesh_.triangles[t][1]];
    const auto& r = mesh_.points[mesh_.triangles[t][2]];
    const double area = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    const double u = ((q[0] - x) * (r[1] - y) - (q[1] - y) * (r[0] - x)) / area;
    const double v = ((r[0] - x) * (p[1] - y) - (r[1] - y) * (p[0] - x)) / area;
    return {u, v, 1 - u - v};
  }
  double distance_to(std::size_t t, double x, double y) const {
    double best = INFINITY;
    for (int e = 0; e < 3; ++e) {
      const auto& a = mesh_.points[mesh_.triangles[t][static_cast<std::size_t>(e)]];
      const auto& b = mesh_.points[mesh_.triangles[t][static_cast<std::size_t>((e + 1) % 3)]];
      const double dx = b[0] - a[0], dy = b[1] - a[1];
      const double len2 = dx * dx + dy * dy;
      const double s = len2 > 0 ? std::clamp(((x - a[0]) * dx + (y - a[1]) * dy) / len2, 0.0, 1.0) : 0;
      best = std::min(best, std::hypot(x - a[0] - s * dx, y - a[1] - s * dy));
    }
    return best;
  }
  Metric interpolate(std::size_t t, const std::array<double, 3>& w) const {
    Metric m{0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const Metric& v = metrics_[mesh_.triangles[t][static_cast<std::size_t>(k)]];
      m.a += w[static_cast<std::size_t>(k)] * v.a;
      m.b += w[static_cast<std::size_t>(k)] * v.b;
      m.c += w[static_cast<std::size_t>(k)] * v.c;
    }
    return m;  // a convex combination of SPD matrices is SPD
  }

  std::string spec_;
  TriangleMesh mesh_;
  std::vector<Metric> metrics_;
  std::array<double, 2> lo_{}, hi_{};
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
  double tolerance_ = 0;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!s.empty() && s.back() == sep) parts.emplace_back();
  return parts;
}

/// Parses the numeric parameters of a built-in field, filling defaults for those omitted.
std::vector<double> parameters(const std::string& spec, const std::vector<std::string>& parts,
                               std::vector<double> defaults, const char* usage) {
  if (parts.size() - 1 > defaults.size())
    throw FieldError("metric field '" + spec + "': too many parameters (usage: " + usage + ")");
  for (std::size_t i = 1; i < parts.size(); ++i) {
    char* end = nullptr;
    const double v = std::strtod(parts[i].c_str(), &end);
    if (parts[i].empty() || *end != '\0' || !std::isfinite(v))
      throw FieldError("metric field '" + spec + "': parameter " + std::to_string(i) + " is '" + parts[i] +
                       "', expected a number (usage: " + usage + ")");
    defaults[i - 1] = v;
  }
  return defaults;
}

/// The .sol path of `mesh:FILE.mesh[:FILE.sol]` (the mesh path with .sol by default).
std::string sol_path(const std::string& spec, const std::vector<std::string>& parts) {
  if (parts.size() < 2 || parts.size() > 3 || parts[1].empty())
    throw FieldError("metric field '" + spec + "': usage mesh:FILE.mesh[:FILE.sol]");
  if (parts.size() == 3) return parts[2];
  const auto dot = parts[1].rfind('.');
  return (dot == std::string::npos ? parts[1] : parts[1].substr(0, dot)) + ".sol";
}

/// The `NAME=EXPR;…` items of an expression field, every name of `names` exactly once.
std::map<std::string, std::string> expression_items(const std::string& spec, const std::string& body,
                                                    const std::vector<std::string>& names) {
  std::map<std::string, std::string> exprs;
  for (const std::string& item : split(body, ';')) {
    const auto eq = item.find('=');
    const std::string key = eq == std::string::npos ? item : item.substr(0, eq);
    if (eq == std::string::npos || std::find(names.begin(), names.end(), key) == names.end()) {
      std::string usage;
      for (const std::string& n : names) usage += (usage.empty() ? "" : ";") + n + "=EXPR";
      throw FieldError("metric field '" + spec + "': expected '" + usage + "', found '" + item + "'");
    }
    if (!exprs.emplace(key, item.substr(eq + 1)).second)
      throw FieldError("metric field '" + spec + "': '" + key + "' is given twice");
  }
  for (const std::string& n : names)
    if (!exprs.count(n)) throw FieldError("metric field '" + spec + "': missing '" + n + "=EXPR'");
  return exprs;
}

std::unique_ptr<MetricField> expression_field(const std::string& spec, const std::string& body,
                                              const std::vector<std::string>& names, bool sizes) {
  return std::make_unique<ExpressionField>(spec, names, expression_items(spec, body, names), sizes);
}

}  // namespace

std::unique_ptr<MetricField> uniform_field(const Metric& m) { return std::make_unique<UniformField>(m); }

std::unique_ptr<MetricField> shock_layer_field(double h_min, double h_max, double width, double x0) {
  return std::make_unique<ShockLayerField>(h_min, h_max, width, x0);
}

std::unique_ptr<MetricField> thesis_field(double h, double ratio, double width, double y0) {
  return std::make_unique<ThesisField>(h, ratio, width, y0);
}

std::unique_ptr<MetricField> parse_metric_field(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string body = colon == std::string::npos ? "" : spec.substr(colon + 1);
  const std::vector<std::string> parts = split(spec, ':');
  if (kind == "uniform") {
    if (parts.size() < 3) throw FieldError("metric field '" + spec + "': usage uniform:H1:H2[:THETA_DEGREES]");
    const auto p = parameters(spec, parts, {0, 0, 0}, "uniform:H1:H2[:THETA_DEGREES]");
    if (!(p[0] > 0) || !(p[1] > 0)) throw FieldError("metric field '" + spec + "': sizes must be positive");
    return std::make_unique<UniformField>(metric_from_sizes(p[0], p[1], p[2] * M_PI / 180),
                                          "uniform:" + exact_number(p[0]) + ":" + exact_number(p[1]) + ":" +
                                              exact_number(p[2]));
  }
  if (kind == "shock") {
    const auto p = parameters(spec, parts, {0.002, 0.1, 0.02, 0.5}, "shock[:HMIN:HMAX:WIDTH:X0]");
    return shock_layer_field(p[0], p[1], p[2], p[3]);
  }
  if (kind == "thesis") {
    const auto p = parameters(spec, parts, {0.05, 4, 0.1, 0.5}, "thesis[:H:RATIO:WIDTH:Y0]");
    return thesis_field(p[0], p[1], p[2], p[3]);
  }
  if (kind == "expr") return expression_field(spec, body, {"a", "b", "c"}, false);
  if (kind == "sizes") return expression_field(spec, body, {"h1", "h2", "theta"}, true);
  if (kind == "mesh") {
    const std::string sol = sol_path(spec, parts);
    TriangleMesh mesh = read_medit_mesh(parts[1]);
    std::vector<Metric> metrics = read_medit_sol(sol, mesh.points.size());
    return std::make_unique<BackgroundMeshField>(spec, std::move(mesh), std::move(metrics));
  }
  throw FieldError("unknown metric field '" + spec +
                   "' (expected uniform:…, shock[:…], thesis[:…], expr:a=…;b=…;c=…, sizes:h1=…;h2=…;theta=… or "
                   "mesh:FILE.mesh[:FILE.sol])");
}

namespace {

std::string point_text(double x, double y, double z) {
  return "(" + number(x) + ", " + number(y) + ", " + number(z) + ")";
}

/// `m`, the value of a 3D field at (x, y, z), if it is a metric; otherwise a FieldError naming the field.
Metric3 checked(const Metric3& m, double x, double y, double z, const MetricField3& field) {
  if (!is_metric(m))
    throw FieldError("metric field '" + field.describe() + "': the matrix [[" + number(m.xx) + ", " + number(m.xy) +
                     ", " + number(m.xz) + "], [" + number(m.xy) + ", " + number(m.yy) + ", " + number(m.yz) + "], [" +
                     number(m.xz) + ", " + number(m.yz) + ", " + number(m.zz) + "]] at " + point_text(x, y, z) +
                     " is not symmetric positive definite");
  return m;
}

/// The size across a shock layer at distance d from its centre (the 2D shock's profile).
double shock_size(double h_min, double h_max, double width, double d) {
  return h_min + (h_max - h_min) * (1 - std::exp(-std::abs(d) / width));
}

class UniformField3 final : public MetricField3 {
public:
  UniformField3(const Metric3& m, std::string description) : m_(m), description_(std::move(description)) {
    if (!is_metric(m)) throw FieldError("uniform field: the matrix is not symmetric positive definite");
  }
  Metric3 at(double, double, double) const override { return m_; }
  std::string describe() const override { return description_; }

private:
  Metric3 m_;
  std::string description_;
};

class PlaneShockField final : public MetricField3 {
public:
  PlaneShockField(double h_min, double h_max, double width, double x0)
      : h_min_(h_min), h_max_(h_max), width_(width), x0_(x0) {
    if (!(h_min > 0) || !(h_max >= h_min) || !(width > 0) || !std::isfinite(h_max) || !std::isfinite(x0))
      throw FieldError("shock field: expected 0 < HMIN <= HMAX, WIDTH > 0 and a finite X0");
  }
  Metric3 at(double x, double y, double z) const override {
    const double across = shock_size(h_min_, h_max_, width_, x - x0_);
    const double along = 1 / (h_max_ * h_max_);
    return checked({1 / (across * across), 0, 0, along, 0, along}, x, y, z, *this);
  }
  std::string describe() const override {
    return "shock:" + number(h_min_) + ":" + number(h_max_) + ":" + number(width_) + ":" + number(x0_);
  }

private:
  double h_min_, h_max_, width_, x0_;
};

class SphereShockField final : public MetricField3 {
public:
  SphereShockField(double h_min, double h_max, double width, double radius, std::array<double, 3> centre)
      : h_min_(h_min), h_max_(h_max), width_(width), radius_(radius), centre_(centre) {
    if (!(h_min > 0) || !(h_max >= h_min) || !(width > 0) || !std::isfinite(h_max) || !(radius >= 0) ||
        !std::isfinite(radius) || !std::isfinite(centre[0]) || !std::isfinite(centre[1]) || !std::isfinite(centre[2]))
      throw FieldError("sphere field: expected 0 < HMIN <= HMAX, WIDTH > 0, R >= 0 and a finite centre");
  }
  Metric3 at(double x, double y, double z) const override {
    const double dx = x - centre_[0], dy = y - centre_[1], dz = z - centre_[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double base = 1 / (h_max_ * h_max_);
    if (!(r > 0)) return {base, 0, 0, base, 0, base};
    const double across = shock_size(h_min_, h_max_, width_, r - radius_);
    // The radial direction is undefined at the centre: the anisotropy fades to zero there, quadratically
    // within min(R, WIDTH) of it (WIDTH when R = 0), so that the field is continuous (a discontinuity
    // is refined forever, thesis §3.5).
    const double fade = std::min(1.0, r / (radius_ > 0 ? std::min(radius_, width_) : width_));
    const double k = (1 / (across * across) - base) * fade * fade;
    const double nx = dx / r, ny = dy / r, nz = dz / r;
    return checked({base + k * nx * nx, k * nx * ny, k * nx * nz, base + k * ny * ny, k * ny * nz, base + k * nz * nz},
                   x, y, z, *this);
  }
  std::string describe() const override {
    return "sphere:" + number(h_min_) + ":" + number(h_max_) + ":" + number(width_) + ":" + number(radius_) + ":" +
           number(centre_[0]) + ":" + number(centre_[1]) + ":" + number(centre_[2]);
  }

private:
  double h_min_, h_max_, width_, radius_;
  std::array<double, 3> centre_;
};

class ExpressionField3 final : public MetricField3 {
public:
  ExpressionField3(std::string spec, const std::vector<std::string>& names, const std::map<std::string, std::string>& exprs)
      : spec_(std::move(spec)), expressions_(spec_, names, exprs) {}
  Metric3 at(double x, double y, double z) const override {
    const auto v = expressions_.at<6>(x, y, z);
    return checked({v[0], v[1], v[2], v[3], v[4], v[5]}, x, y, z, *this);
  }
  std::string describe() const override { return spec_; }

private:
  std::string spec_;
  Expressions expressions_;
};

/// Per-vertex metrics on a tetrahedral mesh, interpolated linearly (barycentric) inside each
/// tetrahedron. Tetrahedra are bucketed in a uniform grid of about one tetrahedron per cell.
class BackgroundTetField final : public MetricField3 {
public:
  BackgroundTetField(std::string spec, TetMesh mesh, std::vector<Metric3> metrics)
      : spec_(std::move(spec)), mesh_(std::move(mesh)), metrics_(std::move(metrics)) {
    if (mesh_.tetrahedra.empty())
      throw FieldError("metric field '" + spec_ + "': the background mesh has no tetrahedra");
    lo_ = hi_ = mesh_.points[mesh_.tetrahedra[0][0]];
    for (const auto& t : mesh_.tetrahedra)
      for (std::size_t v : t)
        for (int k = 0; k < 3; ++k) {
          lo_[k] = std::min(lo_[k], mesh_.points[v][k]);
          hi_[k] = std::max(hi_[k], mesh_.points[v][k]);
        }
    n_ = std::max<std::size_t>(1, static_cast<std::size_t>(std::cbrt(static_cast<double>(mesh_.tetrahedra.size()))));
    cells_.resize(n_ * n_ * n_);
    for (std::size_t i = 0; i < mesh_.tetrahedra.size(); ++i) {
      std::array<double, 3> a = mesh_.points[mesh_.tetrahedra[i][0]], b = a;
      for (std::size_t v : mesh_.tetrahedra[i])
        for (int k = 0; k < 3; ++k) {
          a[k] = std::min(a[k], mesh_.points[v][k]);
          b[k] = std::max(b[k], mesh_.points[v][k]);
        }
      const auto c0 = cell(a), c1 = cell(b);
      for (std::size_t z = c0[2]; z <= c1[2]; ++z)
        for (std::size_t y = c0[1]; y <= c1[1]; ++y)
          for (std::size_t x = c0[0]; x <= c1[0]; ++x) cells_[(z * n_ + y) * n_ + x].push_back(i);
    }
    tolerance_ = 1e-9 * std::max({hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]});
  }

  Metric3 at(double x, double y, double z) const override {
    const std::array<double, 3> p{x, y, z};
    bool inside_box = true;
    for (int k = 0; k < 3; ++k) inside_box = inside_box && p[k] >= lo_[k] - tolerance_ && p[k] <= hi_[k] + tolerance_;
    if (inside_box) {
      const auto c = cell(p);
      // The containing tetrahedron, else (rounding on a face) the least-outside one of the cell.
      double best = -1e-9;
      std::size_t found = mesh_.tetrahedra.size();
      std::array<double, 4> weights{};
      for (std::size_t t : cells_[(c[2] * n_ + c[1]) * n_ + c[0]]) {
        const auto w = barycentric(t, p);
        const double worst = std::min({w[0], w[1], w[2], w[3]});
        if (worst > best) best = worst, found = t, weights = w;
      }
      if (found < mesh_.tetrahedra.size()) {
        double sum = 0;
        for (double& w : weights) sum += (w = std::max(w, 0.0));
        return interpolate(found, weights, sum);
      }
    }
    throw FieldError("metric field '" + spec_ + "': the point " + point_text(x, y, z) +
                     " is outside the background mesh");
  }
  std::string describe() const override { return spec_; }

private:
  std::array<std::size_t, 3> cell(const std::array<double, 3>& p) const {
    std::array<std::size_t, 3> c{};
    for (int k = 0; k < 3; ++k) {
      const double t = hi_[k] > lo_[k] ? (p[k] - lo_[k]) / (hi_[k] - lo_[k]) : 0;
      c[k] = static_cast<std::size_t>(std::clamp(t * static_cast<double>(n_), 0.0, static_cast<double>(n_ - 1)));
    }
    return c;
  }
  std::array<double, 4> barycentric(std::size_t t, const std::array<double, 3>& p) const {
    const auto& tet = mesh_.tetrahedra[t];
    auto volume = [&](const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
                      const std::array<double, 3>& d) {
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
                   w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    };
    const auto& a = mesh_.points[tet[0]];
    const auto& b = mesh_.points[tet[1]];
    const auto& c = mesh_.points[tet[2]];
    const auto& d = mesh_.points[tet[3]];
    const double total = volume(a, b, c, d);
    return {volume(p, b, c, d) / total, volume(a, p, c, d) / total, volume(a, b, p, d) / total,
            volume(a, b, c, p) / total};
  }
  Metric3 interpolate(std::size_t t, const std::array<double, 4>& w, double sum) const {
    Metric3 m{0, 0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < 4; ++k) {
      const Metric3& v = metrics_[mesh_.tetrahedra[t][k]];
      const double c = w[k] / sum;
      m = {m.xx + c * v.xx, m.xy + c * v.xy, m.xz + c * v.xz, m.yy + c * v.yy, m.yz + c * v.yz, m.zz + c * v.zz};
    }
    return m;  // a convex combination of SPD matrices is SPD
  }

  std::string spec_;
  TetMesh mesh_;
  std::vector<Metric3> metrics_;
  std::array<double, 3> lo_{}, hi_{};
  std::size_t n_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
  double tolerance_ = 0;
};

}  // namespace

std::unique_ptr<MetricField3> uniform_field3(const Metric3& m) {
  return std::make_unique<UniformField3>(m, "expr:xx=" + exact_number(m.xx) + ";xy=" + exact_number(m.xy) +
                                                ";xz=" + exact_number(m.xz) + ";yy=" + exact_number(m.yy) +
                                                ";yz=" + exact_number(m.yz) + ";zz=" + exact_number(m.zz));
}

std::unique_ptr<MetricField3> parse_metric_field3(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string body = colon == std::string::npos ? "" : spec.substr(colon + 1);
  const std::vector<std::string> parts = split(spec, ':');
  if (kind == "uniform") {
    if (parts.size() != 4) throw FieldError("metric field '" + spec + "': usage uniform:H1:H2:H3 in 3D");
    const auto p = parameters(spec, parts, {0, 0, 0}, "uniform:H1:H2:H3");
    if (!(p[0] > 0) || !(p[1] > 0) || !(p[2] > 0)) throw FieldError("metric field '" + spec + "': sizes must be positive");
    return std::make_unique<UniformField3>(metric3_from_sizes(p[0], p[1], p[2]), "uniform:" + exact_number(p[0]) + ":" +
                                                                                    exact_number(p[1]) + ":" +
                                                                                    exact_number(p[2]));
  }
  if (kind == "shock") {
    const auto p = parameters(spec, parts, {0.02, 0.2, 0.05, 0.5}, "shock[:HMIN:HMAX:WIDTH:X0]");
    return std::make_unique<PlaneShockField>(p[0], p[1], p[2], p[3]);
  }
  if (kind == "sphere") {
    const auto p = parameters(spec, parts, {0.02, 0.2, 0.05, 0.3, 0.5, 0.5, 0.5}, "sphere[:HMIN:HMAX:WIDTH:R:CX:CY:CZ]");
    return std::make_unique<SphereShockField>(p[0], p[1], p[2], p[3], std::array<double, 3>{p[4], p[5], p[6]});
  }
  if (kind == "expr") {
    const std::vector<std::string> names{"xx", "xy", "xz", "yy", "yz", "zz"};
    return std::make_unique<ExpressionField3>(spec, names, expression_items(spec, body, names));
  }
  if (kind == "mesh") {
    const std::string sol = sol_path(spec, parts);
    TetMesh mesh = read_medit_tet_mesh(parts[1]);
    std::vector<Metric3> metrics = read_medit_sol3(sol, mesh.points.size());
    return std::make_unique<BackgroundTetField>(spec, std::move(mesh), std::move(metrics));
  }
  throw FieldError("unknown 3D metric field '" + spec +
                   "' (expected uniform:H1:H2:H3, shock[:…], sphere[:…], expr:xx=…;xy=…;xz=…;yy=…;yz=…;zz=… or "
                   "mesh:FILE.mesh[:FILE.sol])");
}

double distortion(const MetricField& field, double px, double py, double qx, double qy) {
  return distortion(field.at(px, py), field.at(qx, qy));
}

double bounded_distortion_radius(const MetricField& field, double px, double py, double gamma0, double max_radius,
                                 int rays, int steps) {
  const Metric mp = field.at(px, py);
  const Matrix2 f = square_root(mp);
  // F⁻¹ maps the Euclidean unit circle onto the M(p)-unit circle.
  const double det = f.m00 * f.m11 - f.m01 * f.m10;
  const Matrix2 inv{f.m11 / det, -f.m01 / det, -f.m10 / det, f.m00 / det};
  double radius = max_radius;
  for (int r = 0; r < rays; ++r) {
    const double angle = 2 * M_PI * r / rays;
    const double ux = std::cos(angle), uy = std::sin(angle);
    const double dx = inv.m00 * ux + inv.m01 * uy, dy = inv.m10 * ux + inv.m11 * uy;
    auto bad = [&](double l) { return distortion(mp, field.at(px + l * dx, py + l * dy)) > gamma0; };
    // March outwards to the first sample that breaks the bound, then bisect inside that step.
    double lo = 0, hi = -1;
    for (int k = 1; k <= rays; ++k) {
      const double l = radius * k / rays;
      if (bad(l)) {
        hi = l;
        break;
      }
      lo = l;
    }
    if (hi < 0) continue;
    for (int s = 0; s < steps; ++s) {
      const double mid = 0.5 * (lo + hi);
      (bad(mid) ? hi : lo) = mid;
    }
    radius = std::min(radius, lo);
  }
  return radius;
}

}  // namespace laguerre::core
