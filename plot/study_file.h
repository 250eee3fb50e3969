// The kind of study a study's HDF5 file says it holds (its attribute `study`,
// written by evas study), checked before a figure is drawn from it.
#pragma once

#include <string>

#include "io/hdf5_util.h"

namespace evas {

/// Throws InputError unless the open file `f` (read from `path`) has the
/// attribute study = `kind`: "<prefix: >PATH is not <expected> (no 'study'
/// attribute: a run's results? | a 'K' study's file); <writer>".
void expect_study_file(const h5::Handle& f, const std::string& path, const std::string& kind,
                       const std::string& prefix, const std::string& expected,
                       const std::string& writer);

}  // namespace evas
