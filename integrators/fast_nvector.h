// Faster vector operations for the serial N_Vectors of IDA and CVODE.
#pragma once

#include <sundials/sundials_nvector.h>

namespace evas::sundials {

/// Replaces the weighted norms, linear sums and combinations, scalings and the
/// element-wise operations of the error weights of a serial N_Vector (and of
/// every clone the solver makes of it) by vectorized ones
/// (integrators/fast_nvector.cpp): the library's serial loops sum in one
/// dependent chain, which the compiler may not reorder, and IDA and CVODE take
/// several norms and combinations per step. Also turns on the fused vector
/// operations (one call for IDA's and CVODE's linear combinations).
void use_fast_operations(N_Vector v);

}  // namespace evas::sundials
