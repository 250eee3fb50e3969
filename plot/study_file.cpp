// The kind of study a study's HDF5 file holds (study_file.h).
#include "plot/study_file.h"

#include "model/types.h"

namespace evas {

void expect_study_file(const h5::Handle& f, const std::string& path, const std::string& kind,
                       const std::string& prefix, const std::string& expected,
                       const std::string& writer) {
  const std::string have =
      h5::has_attribute(f, "study") ? h5::read_string_attribute(f, "study") : "";
  if (have == kind) return;
  throw InputError((prefix.empty() ? "" : prefix + ": ") + path + " is not " + expected + " (" +
                   (have.empty() ? std::string("no 'study' attribute: a run's results?")
                                 : "a '" + have + "' study's file") +
                   "); " + writer);
}

}  // namespace evas
