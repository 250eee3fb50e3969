#include "solver/problem.h"

#include <sstream>

namespace evas {

std::string Problem::describe_state(double t, const double* q, const double* v) const {
  std::ostringstream os;
  os << "t = " << t << " s, n = " << size();
  double mq = 0.0, mv = 0.0;
  for (int i = 0; i < size(); ++i) {
    mq = std::max(mq, std::abs(q[i]));
    mv = std::max(mv, std::abs(v[i]));
  }
  os << ", max|q| = " << mq << ", max|v| = " << mv;
  return os.str();
}

}  // namespace evas
