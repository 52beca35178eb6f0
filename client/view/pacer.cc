#include "client/view/pacer.h"

#include <algorithm>

namespace tessera::view {

Pacer::Pacer(Clock::time_point now, double rate, double burst)
    : rate_(rate), burst_(burst), tokens_(burst), at_(now) {}

void Pacer::refill(Clock::time_point now) {
  tokens_ = std::min(burst_, tokens_ + rate_ * std::chrono::duration<double>(now - at_).count());
  at_ = now;
}

bool Pacer::take() {
  if (tokens_ < 1) return false;
  tokens_ -= 1;
  return true;
}

}  // namespace tessera::view
