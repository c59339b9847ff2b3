#include "Closure.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace laguerre::scenarios::detail {

std::vector<std::size_t> cycle_lemma_starts(const std::vector<int>& steps, int k) {
  const std::size_t size = steps.size();
  // First visit of each level below 0 (levels are reached in order because steps are >= -1).
  std::vector<std::size_t> first_visit;  // first_visit[j] = first index with prefix sum -(j+1)
  long long sum = 0, minimum = 0;
  for (std::size_t i = 0; i < size; ++i) {
    sum += steps[i];
    if (sum < minimum) {
      minimum = sum;
      first_visit.push_back(i + 1);
    }
  }
  if (sum != -k) throw std::logic_error("cycle_lemma_starts: the steps do not sum to -k.");
  // Levels M .. M+k-1 (M = the minimum, <= -k, so these levels are all below 0): first_visit entries
  // |M|-1 down to |M|-k. A first visit at the very end (index size) is the rotation starting at 0.
  std::vector<std::size_t> starts;
  const std::size_t depth = first_visit.size();  // = -M >= k
  for (std::size_t level = depth; level + static_cast<std::size_t>(k) > depth; --level) {
    const std::size_t p = first_visit[level - 1];
    starts.push_back(p == size ? 0 : p);
  }
  std::sort(starts.begin(), starts.end());
  return starts;
}

Vertex Blossoming::add_vertex() {
  first_.push_back(core::none);
  return static_cast<Vertex>(first_.size() - 1);
}

void Blossoming::reserve(std::size_t vertices, std::size_t slots) {
  first_.reserve(vertices);
  for (auto* v : {&owner_, &neighbour_, &next_, &prev_, &twin_}) v->reserve(slots);
}

std::uint32_t Blossoming::new_slot(Vertex owner, Vertex neighbour) {
  const auto s = static_cast<std::uint32_t>(owner_.size());
  owner_.push_back(owner);
  neighbour_.push_back(neighbour);
  next_.push_back(s);
  prev_.push_back(s);
  twin_.push_back(core::none);
  return s;
}

std::uint32_t Blossoming::append(Vertex v, Vertex neighbour) {
  if (first_[v] == core::none) {
    const std::uint32_t s = new_slot(v, neighbour);
    first_[v] = s;
    return s;
  }
  return insert_before(first_[v], neighbour);  // just before the first = at the end of the cycle
}

std::uint32_t Blossoming::insert_before(std::uint32_t slot, Vertex neighbour) {
  const std::uint32_t s = new_slot(owner_[slot], neighbour);
  const std::uint32_t p = prev_[slot];
  next_[p] = s;
  prev_[s] = p;
  next_[s] = slot;
  prev_[slot] = s;
  return s;
}

void Blossoming::add_edge(Vertex u, Vertex v) {
  const std::uint32_t a = append(u, v), b = append(v, u);
  twin_[a] = b;
  twin_[b] = a;
}

namespace {

/// A letter of the contour word: a stem (its slot) or an edge side tail → head, given by the slot at the
/// head that points back to the tail (new closure edges ending at the head are inserted just before it).
struct Letter {
  std::uint32_t slot;
  bool is_stem;
};

}  // namespace

std::vector<std::vector<Vertex>> Blossoming::close(unsigned face_degree, unsigned outer_count,
                                                   std::vector<Vertex>* last_before_switch) {
  const std::size_t n = num_vertices();
  if (n == 0 || first_[0] == core::none) throw std::logic_error("close: empty blossoming tree.");
  const unsigned k = face_degree - 1;  // sides needed after a stem
  const int stem_weight = static_cast<int>(face_degree) - 2;

  // Contour word, walking with the tree on the right: after a slot s at v, the next slot is the one
  // clockwise of s at v (for a stem) or clockwise of the arrival slot at the neighbour (for an edge).
  std::vector<Letter> word;
  word.reserve(owner_.size());
  const std::uint32_t start_slot = first_[0];
  std::uint32_t s = start_slot;
  do {
    if (neighbour_[s] == stem) {
      word.push_back({s, true});
      s = prev_[s];
    } else {
      const std::uint32_t arrival = twin_[s];
      word.push_back({arrival, false});
      s = prev_[arrival];
    }
    if (word.size() > owner_.size()) throw std::logic_error("close: the contour does not close up.");
  } while (s != start_slot);
  if (word.size() != owner_.size()) throw std::logic_error("close: the blossoming map is not a tree.");

  // Start right after a minimum of the cyclic walk.
  const std::size_t length = word.size();
  std::size_t start = 0;
  {
    long long sum = 0, minimum = 0;
    for (std::size_t i = 0; i < length; ++i) {
      sum += word[i].is_stem ? stem_weight : -1;
      if (sum < minimum) {
        minimum = sum;
        start = (i + 1) % length;
      }
    }
    if (sum != static_cast<long long>(outer_count))
      throw std::logic_error("close: the tree has " + std::to_string(sum) + " excess stems, expected " +
                             std::to_string(outer_count) + ".");
  }

  // Partial closure with a stack.
  std::vector<Letter> stack;
  stack.reserve(length);
  for (std::size_t i = 0; i < length; ++i) {
    stack.push_back(word[(start + i) % length]);
    while (!stack.back().is_stem && stack.size() > k) {
      const std::size_t top = stack.size();
      bool pattern = stack[top - k - 1].is_stem;
      for (std::size_t j = 1; j <= k && pattern; ++j) pattern = !stack[top - j].is_stem;
      if (!pattern) break;
      const std::uint32_t stem_slot = stack[top - k - 1].slot, arrival = stack[top - 1].slot;
      const Vertex v = owner_[stem_slot], x = owner_[arrival];
      neighbour_[stem_slot] = x;
      const std::uint32_t back = insert_before(arrival, v);
      twin_[stem_slot] = back;
      twin_[back] = stem_slot;
      stack.resize(top - k - 1);
      stack.push_back({back, false});
    }
  }

  // The reduced word: every stem is followed by fewer than k sides, cyclically.
  const std::size_t r = stack.size();
  std::vector<unsigned> run(r, 0);  // for stems: number of sides that follow
  std::vector<std::size_t> stems;
  for (std::size_t i = 0; i < r; ++i)
    if (stack[i].is_stem) {
      stems.push_back(i);
      std::size_t j = (i + 1) % r;
      while (!stack[j].is_stem) {
        ++run[i];
        j = (j + 1) % r;
      }
      if (run[i] >= k) throw std::logic_error("close: a closable stem survived the partial closure.");
    }
  if (stems.empty()) throw std::logic_error("close: no stem is left for the complete closure.");

  // Complete closure. advance = k - 1 - run; the advances sum to outer_count. Start on a stem whose
  // predecessor stem advanced (the first stem of an outer vertex).
  const auto advance = [&](std::size_t i) { return k - 1 - run[stems[i]]; };
  std::size_t first_stem = 0;
  while (advance((first_stem + stems.size() - 1) % stems.size()) == 0) ++first_stem;
  std::vector<std::vector<Vertex>> segment(outer_count);
  unsigned c = 0;
  for (std::size_t t = 0; t < stems.size(); ++t) {
    const std::size_t i = (first_stem + t) % stems.size();
    if (c >= outer_count) throw std::logic_error("close: the complete closure went round more than once.");
    const std::uint32_t slot = stack[stems[i]].slot;
    neighbour_[slot] = static_cast<Vertex>(n + c);
    segment[c].push_back(owner_[slot]);
    c += advance(i);
  }
  if (c != outer_count) throw std::logic_error("close: the complete closure did not go round once.");

  std::vector<std::vector<Vertex>> rotation(n + outer_count);
  for (Vertex v = 0; v < n; ++v) {
    std::uint32_t t = first_[v];
    do {
      rotation[v].push_back(neighbour_[t]);
      t = next_[t];
    } while (t != first_[v]);
  }
  if (last_before_switch) last_before_switch->assign(outer_count, core::none);
  for (unsigned j = 0; j < outer_count; ++j) {
    auto& rot = rotation[n + j];
    rot = std::move(segment[j]);
    if (last_before_switch && !rot.empty()) (*last_before_switch)[j] = rot.back();
    if (outer_count == 2) {
      rot.push_back(static_cast<Vertex>(n + 1 - j));
    } else {
      rot.push_back(static_cast<Vertex>(n + (j + 1) % outer_count));
      rot.push_back(static_cast<Vertex>(n + (j + outer_count - 1) % outer_count));
    }
  }
  return rotation;
}

}  // namespace laguerre::scenarios::detail
