// Vectorized vector operations for serial N_Vectors (see fast_nvector.h).
// Same definitions as the library's (SUNDIALS user guide, N_Vector
// operations): WSqrSumLocal = sum (x_i w_i)^2, WrmsNorm = sqrt(WSqrSumLocal / n),
// WrmsNormMask = the same over the components with id_i > 0. Eigen sums in
// several independent partial sums (SIMD), so the last bits may differ from
// the library's single running sum.
#include "integrators/fast_nvector.h"

#include <nvector/nvector_serial.h>

#include <cmath>

#include "model/types.h"

namespace evas::sundials {
namespace {

Eigen::Map<const Vec> view(N_Vector v) {
  return {NV_DATA_S(v), static_cast<Eigen::Index>(NV_LENGTH_S(v))};
}

realtype wsqrsum(N_Vector x, N_Vector w) { return view(x).cwiseProduct(view(w)).squaredNorm(); }

realtype wrms(N_Vector x, N_Vector w) {
  const auto n = NV_LENGTH_S(x);
  return n > 0 ? std::sqrt(wsqrsum(x, w) / static_cast<realtype>(n)) : 0.0;
}

realtype wsqrsum_mask(N_Vector x, N_Vector w, N_Vector id) {
  return (view(id).array() > 0.0).select(view(x).cwiseProduct(view(w)), 0.0).squaredNorm();
}

realtype wrms_mask(N_Vector x, N_Vector w, N_Vector id) {
  const auto n = NV_LENGTH_S(x);
  return n > 0 ? std::sqrt(wsqrsum_mask(x, w, id) / static_cast<realtype>(n)) : 0.0;
}

Eigen::Map<Vec> view_out(N_Vector v) {
  return {NV_DATA_S(v), static_cast<Eigen::Index>(NV_LENGTH_S(v))};
}

// z = sum c_i X_i (z may be X[0], as the library allows; any other alias
// takes the element-wise loop).
int linear_combination(int nvec, realtype* c, N_Vector* X, N_Vector z) {
  if (nvec < 1) return -1;
  for (int i = 1; i < nvec; ++i)
    if (X[i] == z) {
      const auto n = NV_LENGTH_S(z);
      for (sunindextype j = 0; j < n; ++j) {
        realtype sum = 0.0;
        for (int k = 0; k < nvec; ++k) sum += c[k] * NV_DATA_S(X[k])[j];
        NV_DATA_S(z)[j] = sum;
      }
      return 0;
    }
  auto Z = view_out(z);
  if (X[0] == z) {
    if (c[0] != 1.0) Z *= c[0];
  } else {
    Z = c[0] * view(X[0]);
  }
  for (int i = 1; i < nvec; ++i) Z += c[i] * view(X[i]);
  return 0;
}

void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  view_out(z) = a * view(x) + b * view(y);  // element-wise: any alias is safe
}

void scale(realtype c, N_Vector x, N_Vector z) { view_out(z) = c * view(x); }

void constant(realtype c, N_Vector z) { view_out(z).setConstant(c); }

void absolute(N_Vector x, N_Vector z) { view_out(z) = view(x).cwiseAbs(); }

void inverse(N_Vector x, N_Vector z) { view_out(z) = view(x).cwiseInverse(); }

void add_constant(N_Vector x, realtype b, N_Vector z) { view_out(z) = view(x).array() + b; }

// Z[i] = c[i] X[i] (Z[i] may be X[i])
int scale_vector_array(int nvec, realtype* c, N_Vector* X, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) view_out(Z[i]) = c[i] * view(X[i]);
  return 0;
}

// Z[i] = a X[i] + b Y[i] (element-wise: Z[i] may be X[i] or Y[i])
int linear_sum_vector_array(int nvec, realtype a, N_Vector* X, realtype b, N_Vector* Y,
                            N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) view_out(Z[i]) = a * view(X[i]) + b * view(Y[i]);
  return 0;
}

// Z[i] = a[i] x + Y[i] (element-wise: Z[i] may be Y[i])
int scale_add_multi(int nvec, realtype* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) view_out(Z[i]) = a[i] * view(x) + view(Y[i]);
  return 0;
}

void product(N_Vector x, N_Vector y, N_Vector z) { view_out(z) = view(x).cwiseProduct(view(y)); }

void quotient(N_Vector x, N_Vector y, N_Vector z) { view_out(z) = view(x).cwiseQuotient(view(y)); }

}  // namespace

void use_fast_operations(N_Vector v) {
  N_VEnableFusedOps_Serial(v, SUNTRUE);
  v->ops->nvwsqrsumlocal = wsqrsum;
  v->ops->nvwrmsnorm = wrms;
  v->ops->nvwsqrsummasklocal = wsqrsum_mask;
  v->ops->nvwrmsnormmask = wrms_mask;
  v->ops->nvlinearcombination = linear_combination;
  v->ops->nvlinearsum = linear_sum;
  v->ops->nvscale = scale;
  v->ops->nvconst = constant;
  v->ops->nvabs = absolute;
  v->ops->nvinv = inverse;
  v->ops->nvaddconst = add_constant;
  v->ops->nvscalevectorarray = scale_vector_array;
  v->ops->nvlinearsumvectorarray = linear_sum_vector_array;
  v->ops->nvscaleaddmulti = scale_add_multi;
  v->ops->nvprod = product;
  v->ops->nvdiv = quotient;
}

}  // namespace evas::sundials
