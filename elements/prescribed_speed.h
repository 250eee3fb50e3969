// The crank speed an element prescribes (a piston in mode prescribed, the
// motor's driver): its own constant `speed`, or, once the scene reader hands
// it over, the crank's speed profile (model/element.h, "The crank's speed").
// The elements keep one of these and forward Element::own_speed, wants_speed
// and follow_speed to it.
#pragma once

#include "model/speed_profile.h"

namespace evas {

class PrescribedSpeed {
 public:
  explicit PrescribedSpeed(double own) : profile_(SpeedProfile::constant(own)) {}
  /// No speed of its own: wait for the crank's.
  void leave_to_crank() { source_ = Source::waiting; }
  /// The element's own speed, or null while it waits for or follows the crank.
  const SpeedProfile* own() const { return source_ == Source::own ? &profile_ : nullptr; }
  bool waiting() const { return source_ == Source::waiting; }
  void follow(const SpeedProfile& crank) {
    profile_ = crank;
    source_ = Source::crank;
  }
  /// The speed in use (angle turned since t = 0, speed, acceleration).
  const SpeedProfile& profile() const { return profile_; }

 private:
  enum class Source { own, waiting, crank };
  Source source_ = Source::own;
  SpeedProfile profile_;
};

}  // namespace evas
