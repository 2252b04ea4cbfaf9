#include "pivoting/regularization.h"

#include <algorithm>
#include <cmath>

#include "pivoting/tuning.h"

namespace ode_bpp::pivoting {

bool Regularization::raise_target() {
    const double next = target_ == 0 ? tuning::kFirstShift * max_diag_ : target_ * tuning::kShiftGrowth;
    if (!(next > target_) || next > tuning::kLastShift * max_diag_ * (1 + 1e-9)) return false;
    target_ = next;
    return true;
}

double Regularization::continuation(int k, int stages) const {
    return tuning::kContinuationStart * max_diag_ * std::pow(tuning::kContinuationSpan, double(k) / stages);
}

RescueSchedule::RescueSchedule(const Regularization& r)
    : max_diag_(r.max_diag()),
      target_(r.target()),
      delta_(std::max(r.target(), tuning::kRescueStart * r.max_diag())),
      ratio_(tuning::kRescueFirstRatio) {}

void RescueSchedule::converged(int steps) {
    if (accepted_ > 0 && steps <= 1) ratio_ = std::max(ratio_ * ratio_, tuning::kRescueMinRatio);
    accepted_ = delta_;
    next_delta();
}

bool RescueSchedule::stalled() {
    if (accepted_ < 0) {  // not even the first stage converged: more regularization, x10 per try
        if (delta_ >= tuning::kRescueCeiling * max_diag_) return false;
        delta_ *= 10;
        return true;
    }
    ratio_ = std::sqrt(ratio_);
    if (ratio_ > tuning::kRescueMaxRatio) return false;
    next_delta();
    return true;
}

void RescueSchedule::next_delta() {
    delta_ = accepted_ * ratio_;
    if (delta_ < tuning::kRescueFloor * max_diag_ || delta_ <= target_) delta_ = target_;
}

}  // namespace ode_bpp::pivoting
