#pragma once
// A scalar cell field on a Grid2D, ghosts included (same indexing as Grid2D::index).
#include <vector>

#include "solver/core/grid.hpp"

namespace dustlift {

class Field2D {
 public:
  Field2D() = default;
  Field2D(const Grid2D& grid, double value = 0.0)
      : stride_(grid.stride()), ng_(grid.ghosts()), data_(grid.size_with_ghosts(), value) {}

  double& operator()(int i, int j) { return data_[idx(i, j)]; }
  double operator()(int i, int j) const { return data_[idx(i, j)]; }
  double* data() { return data_.data(); }
  const double* data() const { return data_.data(); }
  std::size_t size() const { return data_.size(); }
  void fill(double v) { std::fill(data_.begin(), data_.end(), v); }
  std::vector<double>& raw() { return data_; }
  const std::vector<double>& raw() const { return data_; }

 private:
  std::size_t idx(int i, int j) const {
    return static_cast<std::size_t>((j + ng_) * stride_ + (i + ng_));
  }
  int stride_ = 0;
  int ng_ = 0;
  std::vector<double> data_;
};

}  // namespace dustlift
