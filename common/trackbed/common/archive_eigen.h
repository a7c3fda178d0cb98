// Eigen's fixed-size vectors in the config archive (archive.h): a Vector2d is a list
// of two numbers, `[1.5, -2]`. Include it wherever a struct with such members is read
// or written, so that the codec is seen before its first use.
#pragma once

#include <string>

#include <Eigen/Core>

#include "trackbed/common/archive.h"

namespace trackbed::archive {

/// Eigen::Matrix<double, N, 1> as a list of exactly N numbers.
template <int N>
struct Codec<Eigen::Matrix<double, N, 1>> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   Eigen::Matrix<double, N, 1>* value) {
    if (!node.IsList() || node.size() != static_cast<std::size_t>(N)) {
      throw Error(path, "expected a list of " + std::to_string(N) + " numbers, got " +
                            Describe(node, wording));
    }
    for (int i = 0; i < N; ++i) {
      Codec<double>::Read(node.items()[static_cast<std::size_t>(i)],
                          JoinIndex(path, static_cast<std::size_t>(i)), wording, &(*value)[i]);
    }
  }
  static Node Write(const Eigen::Matrix<double, N, 1>& value) {
    Node list = Node::List();
    for (int i = 0; i < N; ++i) list.items().push_back(Codec<double>::Write(value[i]));
    return list;
  }
};

}  // namespace trackbed::archive
