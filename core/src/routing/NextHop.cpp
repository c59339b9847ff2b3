#include "laguerre/core/routing/NextHop.hpp"

#include "NextHopRules.hpp"

namespace laguerre::core {

bool leaves_perimeter(Point2 holder, Point2 entry, Point2 t) {
  return compare_distance(t, holder, entry) == Sign::negative;
}

#define LAGUERRE_NEXT_HOP_INSTANTIATE(View)                                                      \
  template std::size_t greedy_power_hop(const View&, Point2);                                    \
  template std::size_t greedy_euclid_hop(const View&, Point2);                                   \
  template std::size_t compass_hop(const View&, Point2);                                         \
  template std::size_t first_face_hop(const View&, Point2);                                      \
  template FaceHop face_hop(const View&, Point2, Point2, FaceChange&, std::size_t);
LAGUERRE_NEXT_HOP_INSTANTIATE(GraphView)
LAGUERRE_NEXT_HOP_INSTANTIATE(NeighbourView)
#undef LAGUERRE_NEXT_HOP_INSTANTIATE
template std::size_t greedy_power_hop(const GraphView128&, Point128);
template std::size_t greedy_euclid_hop(const GraphView128&, Point128);

}  // namespace laguerre::core
