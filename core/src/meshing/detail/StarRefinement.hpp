#pragma once
// The refinement loop shared by the 2D and 3D star meshers (StarMesher.cpp, StarMesher3.cpp), and the
// state it drives: the priority queue of refinement requests and the stack of dirty stars.
//
// One step of the loop does the most urgent of: stop (too many sites, or a reason the mesher gives);
// split a queued constraint (subsegment, crease); refine the top request if its star is clean and has
// not changed since; recompute every dirty star; else sweep for inconsistent elements. A sweep finding
// none converges (after the mesher's last-resort rule, if it has one); sweeps that insert nothing more
// than `idle_sweeps` times in a row end as stuck. Then the mesher merges its stars into the result and
// a converged result is checked to be a mesh of the domain.
//
// A mesher derives from StarRefinement<itself, its Request, its Index> and provides, for the base:
//   std::size_t site_count() const;              the sites so far
//   std::string stop_reason() const;             why refinement must stop now, or ""
//   bool split_queued_constraint();              pops and handles one queued constraint; false if none
//   std::uint32_t star_version(Index v) const;   the version of v's star (Request::version is one)
//   void refine(const Request&);                 handles a current request of a clean star
//   void update_star(Index v);                   recomputes v's star (it then queues its requests)
//   bool consistency_sweep();                    queues the inconsistent elements; false if none
//   bool last_resort();                          a rule for after convergence; true if it did something
//   void merge(Result&) const;                   the mesh, metrics and statistics
//   std::string check(const Result&) const;      "" for a mesh of the domain, else the problem
#include <cstddef>
#include <cstdint>
#include <queue>
#include <string>
#include <vector>

namespace laguerre::core::detail {

/// The words of the loop's statuses: "triangles" / "tetrahedra", "triangulation" / "tetrahedralization".
struct ElementWords {
  const char* elements;  ///< plural of the mesh's elements
  const char* whole;     ///< what their union must be
};

template <class Mesher, class Request, class Index>
class StarRefinement {
protected:
  /// Marks v's star for recomputation (once until it is recomputed).
  void mark_dirty(Index v) {
    if (!is_dirty_[v]) {
      is_dirty_[v] = true;
      dirty_.push_back(v);
    }
  }

  /// Runs the loop of the file comment until convergence or a stop, and returns the merged result.
  template <class Result>
  Result refine_until_done(std::size_t max_vertices, int idle_sweeps, ElementWords words) {
    Mesher& m = static_cast<Mesher&>(*this);
    Result result;
    std::size_t sites_at_last_sweep = 0;
    int idle = 0;
    while (true) {
      if (m.site_count() > max_vertices) {
        result.status = "stopped at " + std::to_string(m.site_count()) + " vertices (max_vertices)";
        break;
      }
      if (std::string why = m.stop_reason(); !why.empty()) {
        result.status = "stopped: " + why;
        break;
      }
      if (m.split_queued_constraint()) continue;
      // Refine from clean stars first: a request of a star made dirty by an insertion since is
      // dropped (its star is re-evaluated when recomputed), so stars are recomputed once per batch of
      // insertions rather than after every insertion.
      if (!requests_.empty()) {
        const Request r = requests_.top();
        requests_.pop();
        if (r.version == m.star_version(r.v) && !is_dirty_[r.v]) m.refine(r);
        continue;
      }
      if (!dirty_.empty()) {
        while (!dirty_.empty()) {
          const Index v = dirty_.back();
          dirty_.pop_back();
          is_dirty_[v] = false;
          m.update_star(v);
        }
        continue;
      }
      if (!m.consistency_sweep()) {
        if (m.last_resort()) continue;
        result.converged = true;
        result.status = "converged";
        break;
      }
      if (m.site_count() == sites_at_last_sweep) {
        if (++idle > idle_sweeps) {
          result.status = std::string("stuck: inconsistent ") + words.elements +
                          " remain but no refinement point could be inserted";
          break;
        }
      } else {
        idle = 0;
      }
      sites_at_last_sweep = m.site_count();
    }
    m.merge(result);
    // Consistent stars whose union is not a mesh of the domain would be a bug of the star
    // computation; never report such a mesh as converged.
    if (result.converged)
      if (std::string problem = m.check(result); !problem.empty()) {
        result.converged = false;
        result.status = std::string("not a ") + words.whole + " although every star is consistent: " + problem;
      }
    return result;
  }

  std::priority_queue<Request> requests_;  ///< refinement requests, most urgent on top
  std::vector<bool> is_dirty_;             ///< per site: its star awaits recomputation
  std::vector<Index> dirty_;               ///< the sites whose star awaits recomputation
};

}  // namespace laguerre::core::detail
