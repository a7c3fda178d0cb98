// Eigen's fixed-size vectors and matrices in the config archive (archive.h): a Vector2d
// is a list of two numbers, `[1.5, -2]`; a matrix is a list of its rows; a rigid
// transform (Isometry3d) is its 4 × 4 matrix, checked to be one when read. Include it wherever a
// struct with such members is read or written, so that the codec is seen before its first use.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Geometry>

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

/// Eigen::Matrix<double, R, C> (C > 1) as a list of R rows, each a list of C numbers.
template <int R, int C>
struct Codec<Eigen::Matrix<double, R, C>, std::enable_if_t<(C > 1)>> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   Eigen::Matrix<double, R, C>* value) {
    if (!node.IsList() || node.size() != static_cast<std::size_t>(R)) {
      throw Error(path, "expected a list of " + std::to_string(R) + " rows, got " +
                            Describe(node, wording));
    }
    for (int r = 0; r < R; ++r) {
      Eigen::Matrix<double, C, 1> row;
      Codec<Eigen::Matrix<double, C, 1>>::Read(node.items()[static_cast<std::size_t>(r)],
                                               JoinIndex(path, static_cast<std::size_t>(r)),
                                               wording, &row);
      value->row(r) = row.transpose();
    }
  }
  static Node Write(const Eigen::Matrix<double, R, C>& value) {
    Node rows = Node::List();
    for (int r = 0; r < R; ++r) {
      rows.items().push_back(Codec<Eigen::Matrix<double, C, 1>>::Write(value.row(r).transpose()));
    }
    return rows;
  }
};

/// A rigid transform as its 4 × 4 matrix: the last row 0 0 0 1 and the rotation
/// orthonormal (to 1e-6) with determinant +1, else an Error at `path`.
template <>
struct Codec<Eigen::Isometry3d> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   Eigen::Isometry3d* value) {
    Eigen::Matrix4d T;
    Codec<Eigen::Matrix4d>::Read(node, path, wording, &T);
    if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
      throw Error(path, "not a rigid transform: the last row is not 0 0 0 1");
    }
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6) ||
        !(R.determinant() > 0)) {
      throw Error(path,
                  "not a rigid transform: the rotation is not orthonormal with determinant +1");
    }
    value->matrix() = T;
  }
  static Node Write(const Eigen::Isometry3d& value) {
    return Codec<Eigen::Matrix4d>::Write(value.matrix());
  }
};

}  // namespace trackbed::archive
