// NumPy arrays and SciPy's compressed-column parts for the compiled Python
// module (evas_module.cpp, problem_binding.cpp).
#pragma once

#include <pybind11/numpy.h>

#include <algorithm>
#include <string>

#include "model/types.h"

namespace evas::py_util {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

inline Vec to_vec(const Array& a, long n, const char* what) {
  if (a.ndim() != 1 || a.shape(0) != n)
    throw InputError(std::string(what) + ": expected a vector of length " + std::to_string(n));
  return Eigen::Map<const Vec>(a.data(), n);
}

inline Array to_array(const Vec& v) {
  Array a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

// (data, indices, indptr, (rows, cols)) of a compressed-column matrix
inline py::tuple csc_parts(const SpMat& A) {
  SpMat c = A;
  c.makeCompressed();
  Array data(c.nonZeros());
  py::array_t<long> indices(c.nonZeros()), indptr(c.cols() + 1);
  for (long k = 0; k < c.nonZeros(); ++k) {
    data.mutable_data()[k] = c.valuePtr()[k];
    indices.mutable_data()[k] = c.innerIndexPtr()[k];
  }
  for (long k = 0; k <= c.cols(); ++k) indptr.mutable_data()[k] = c.outerIndexPtr()[k];
  return py::make_tuple(data, indices, indptr, py::make_tuple(c.rows(), c.cols()));
}

}  // namespace evas::py_util
