#pragma once
// The lookup of a node's neighbour index by id, shared by the nodes that keep a neighbour list.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols::detail {

/// (id, index) pairs of `neighbours`, sorted by id, for neighbour_index. Throws std::invalid_argument
/// (naming the node `self`) if the list is empty, too long, names `self` or names a neighbour twice.
std::vector<std::pair<NodeId, std::uint32_t>> sorted_neighbours(NodeId self, const std::vector<NodeId>& neighbours);

/// The index of neighbour `id` in the list `sorted` was built from, or `sorted.size()` if `id` is none.
std::size_t neighbour_index(const std::vector<std::pair<NodeId, std::uint32_t>>& sorted, NodeId id);

}  // namespace laguerre::protocols::detail
