// The film force of a journal bearing in its plane, as every film model
// (short, finite, reynolds: elements/journal_bearing.h) returns it.
#pragma once

#include <Eigen/Dense>

namespace evas {

/// Film force of one station in the bearing plane (2-D, bearing components):
/// force on the journal and its partial derivatives.
struct FilmForce {
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  Eigen::Matrix2d df_de = Eigen::Matrix2d::Zero();   ///< d f / d e
  Eigen::Matrix2d df_ded = Eigen::Matrix2d::Zero();  ///< d f / d edot
  Eigen::Vector2d df_dom = Eigen::Vector2d::Zero();  ///< d f / d omega
};

}  // namespace evas
