#include "latsim/radio/edca.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace latsim::radio {

EdcaParams EdcaParams::for_category(std::string_view ac) {
  // aCWmin 15 and aCWmax 1023 of the OFDM PHY; TXOP limits of Table 9-155.
  if (ac == "BK") return EdcaParams{7, 15, 1023, des::Time::zero()};
  if (ac == "BE") return EdcaParams{3, 15, 1023, des::Time::zero()};
  if (ac == "VI") return EdcaParams{2, 7, 15, des::Time::us(3008)};
  if (ac == "VO") return EdcaParams{2, 3, 7, des::Time::us(1504)};
  throw std::invalid_argument("access category must be BK, BE, VI or VO, not \"" + std::string(ac) + "\"");
}

des::Time Backoff::counting_start(des::Time access) const {
  return std::max(start_, access + slot_ * p_.aifsn);
}

void Backoff::count_down(des::Time access, des::Time now) {
  const des::Time from = counting_start(access);
  if (from > now) return;
  // Boundaries from, from + slot, ... up to now: each one decrements.
  const int64_t boundaries = (now - from) / slot_ + 1;
  const int n = static_cast<int>(std::min<int64_t>(boundaries, slots_));
  slots_ -= n;
  start_ = from + slot_ * n;
}

void Backoff::on_arrival(des::Time access, des::Time now, bool medium_busy, des::RandomStream& stream) {
  // While the medium is busy the counter is frozen where the last access left it.
  if (!medium_busy) count_down(access, now);
  if (slots_ != 0) return;
  if (medium_busy) {
    draw(now, stream);
    return;
  }
  // Idle medium, counter at zero: transmit at the first boundary after now
  // (EDCA acts at slot boundaries only), or at the end of AIFS if later.
  const des::Time aifs_end = access + slot_ * p_.aifsn;
  if (now > aifs_end) start_ = aifs_end + slot_ * ((now - aifs_end) / slot_ + 1);
  else start_ = aifs_end;
}

void Backoff::draw(des::Time now, des::RandomStream& stream) {
  slots_ = static_cast<int>(stream.uniform_int(static_cast<uint64_t>(cw_) + 1));
  start_ = now;
}

void Backoff::double_cw() { cw_ = std::min(2 * (cw_ + 1) - 1, p_.cw_max); }

}  // namespace latsim::radio
