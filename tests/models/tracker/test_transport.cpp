// Links from tracker to host (direct, serial poll, serial interrupt, USB HID) and the mailbox.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "latsim/tracker/transport.hpp"

using namespace latsim::tracker;
using latsim::des::PeriodicSchedule;
using latsim::des::RationalSeconds;
using latsim::des::Time;

namespace {

SerialLinkParams serial(SerialLinkParams::HostMode mode) {
  SerialLinkParams p;
  p.record_bytes = 32;
  p.bits_per_byte = 10;
  p.baud = 19200.0;
  p.host_mode = mode;
  return p;
}

TrackerSample sample_number(int64_t k) {
  TrackerSample s;
  s.index = k;
  s.measured_at = Time::ms(10 * k);
  s.ready_at = s.measured_at;
  return s;
}

}  // namespace

TEST_CASE("direct link delivers at once and checks order", "[transport]") {
  DirectLink link;
  CHECK(link.deliver(Time::ms(5)) == Time::ms(5));
  CHECK(link.deliver(Time::ms(5)) == Time::ms(5));
  CHECK_THROWS_AS(link.deliver(Time::ms(4)), std::logic_error);
}

TEST_CASE("serial transmit time is record bits over baud", "[transport]") {
  const SerialLink link(serial(SerialLinkParams::Interrupt));
  // 32 bytes * 10 bits / 19200 baud = 16.666... ms.
  CHECK(std::abs((link.transmit_time() - Time::from_seconds(320.0 / 19200.0)).ticks()) <= 1);
  CHECK(std::abs((link.character_time() - Time::from_seconds(10.0 / 19200.0)).ticks()) <= 1);
  SerialLinkParams p = serial(SerialLinkParams::Interrupt);
  p.record_bytes = 12;
  p.bits_per_byte = 11;
  p.baud = 9600.0;
  CHECK(std::abs((SerialLink(p).transmit_time() - Time::from_seconds(132.0 / 9600.0)).ticks()) <= 1);
}

TEST_CASE("interrupt mode delivers with the last character and records queue", "[transport]") {
  SerialLink link(serial(SerialLinkParams::Interrupt));
  const Time tx = link.transmit_time();
  CHECK(link.deliver(Time::ms(100)) == Time::ms(100) + tx);
  // Two records ready together: the second waits for the line.
  CHECK(link.deliver(Time::ms(200)) == Time::ms(200) + tx);
  const Time second = link.deliver(Time::ms(200));
  CHECK(std::abs((second - (Time::ms(200) + Time::from_seconds(640.0 / 19200.0))).ticks()) <= 1);
  CHECK_THROWS_AS(link.deliver(Time::ms(150)), std::logic_error);
}

TEST_CASE("per-character interrupt cost delays the record, with backlog when slow", "[transport]") {
  SerialLinkParams fast = serial(SerialLinkParams::Interrupt);
  fast.per_char_interrupt_cost = Time::us(100);  // under the 520.8 us character time
  SerialLink fast_link(fast);
  CHECK(fast_link.deliver(Time::zero()) == fast_link.transmit_time() + Time::us(100));

  SerialLinkParams slow = serial(SerialLinkParams::Interrupt);
  slow.per_char_interrupt_cost = Time::us(600);  // handlers fall behind the line
  SerialLink slow_link(slow);
  // Handlers run back to back from the first character's arrival.
  CHECK(slow_link.deliver(Time::zero()) == slow_link.character_time() + Time::us(600) * 32);
}

TEST_CASE("polling delivers at the first poll at or after completion", "[transport]") {
  SerialLinkParams p = serial(SerialLinkParams::Poll);
  p.poll_interval = Time::ms(30);
  p.poll_clock.phase = Time::ms(7);
  SerialLink link(p);
  const Time tx = link.transmit_time();
  // Ready at 0: complete at 16.67 ms, next poll at 37 ms.
  CHECK(link.deliver(Time::zero()) == Time::ms(37));
  // Complete exactly on a poll: delivered on that poll.
  CHECK(link.deliver(Time::ms(67) - tx) == Time::ms(67));
  CHECK(link.deliver(Time::ms(67) - tx + Time::ps(1)) > Time::ms(67));
}

TEST_CASE("polling adds a wait uniform between 0 and the poll interval", "[transport]") {
  SerialLinkParams p = serial(SerialLinkParams::Poll);
  p.baud = 38400.0;  // transmission (8.3 ms) well under the tracker period
  p.poll_interval = Time::ms(30);
  SerialLink link(p);
  const PeriodicSchedule tracker(Time::zero(), RationalSeconds::period_of_hz(60000, 1001));
  const int n = 18000;
  double sum_ms = 0.0;
  Time lo = Time::max();
  Time hi = Time::zero();
  std::array<int, 10> bins{};
  for (int k = 0; k < n; ++k) {
    const Time ready = tracker.at(k);
    const Time wait = link.deliver(ready) - (ready + link.transmit_time());
    lo = std::min(lo, wait);
    hi = std::max(hi, wait);
    sum_ms += wait.to_ms();
    ++bins.at(static_cast<size_t>(wait.to_ms() / 3.0));
  }
  CHECK(lo >= Time::zero());
  CHECK(hi < Time::ms(30));
  CHECK(lo < Time::us(100));
  CHECK(hi > Time::us(29900));
  CHECK(sum_ms / n == Approx(15.0).epsilon(0.01));
  for (int count : bins) CHECK(count == Approx(n / 10).epsilon(0.05));
}

TEST_CASE("mailbox returns the newest of several records found by one poll", "[mailbox]") {
  SampleMailbox box;
  CHECK_FALSE(box.newest_at(Time::s(1)).has_value());
  const Time poll = Time::ms(60);
  box.deliver(sample_number(1), poll);
  box.deliver(sample_number(2), poll);
  box.deliver(sample_number(3), poll);
  box.deliver(sample_number(4), Time::ms(90));
  CHECK_FALSE(box.newest_at(poll - Time::ps(1)).has_value());
  CHECK(box.newest_at(poll)->index == 3);
  CHECK(box.newest_at(Time::ms(89))->index == 3);
  CHECK(box.newest_at(Time::ms(90))->index == 4);
  CHECK(box.held() == 2);  // 1 and 2 can never be returned

  CHECK(box.read(Time::ms(70))->index == 3);
  CHECK(box.read(Time::ms(80))->index == 3);  // nothing new: reuse the last sample
  CHECK(box.read(Time::ms(95))->index == 4);
  CHECK(box.skipped_count() == 2);
}

TEST_CASE("mailbox ignores stale records and keeps memory bounded", "[mailbox]") {
  SampleMailbox box;
  box.deliver(sample_number(5), Time::ms(50));
  box.deliver(sample_number(4), Time::ms(60));  // older and later: never visible
  CHECK(box.newest_at(Time::ms(70))->index == 5);
  // A newer record arriving earlier than a queued older one replaces it.
  box.deliver(sample_number(7), Time::ms(100));
  box.deliver(sample_number(8), Time::ms(95));
  CHECK(box.newest_at(Time::ms(99))->index == 8);
  CHECK(box.newest_at(Time::ms(100))->index == 8);
  CHECK(box.held() == 2);

  SampleMailbox stream;
  size_t most = 0;
  for (int64_t k = 0; k < 1000; ++k) {
    stream.deliver(sample_number(k), Time::ms(10 * k + 25));
    if (k % 3 == 0) (void)stream.read(Time::ms(10 * k));
    most = std::max(most, stream.held());
  }
  CHECK(most <= 6);
}

TEST_CASE("USB HID: a report waits for the next poll, then the operating system's delay") {
  // Reports every 997 us against polls every P = 1e6/poll_hz us, poll phase
  // 0: 997 and P (a multiple of 1000) are coprime, so over P reports the
  // wait to the poll, (-t) mod P, takes each whole microsecond 0 .. P-1 once:
  // its mean is (P - 1 us) / 2 exactly, its maximum P - 1 us.
  for (const int64_t hz : {125, 250, 500, 1000}) {
    UsbHidParams p;
    p.poll_hz = hz;
    p.poll_clock.phase = Time::zero();
    p.os_delay = Time::us(1500);
    UsbHidLink link(p, latsim::des::RandomStream(1, "test.usb"));
    const int64_t period_us = 1000000 / hz;
    int64_t sum_us = 0, max_us = 0;
    for (int64_t i = 0; i < period_us; ++i) {
      const Time start = Time::us(997 * i);
      const Carriage c = link.carry(start);
      const int64_t added = (c.visible - start).ticks();
      REQUIRE(added % 1000000 == 0);  // whole microseconds: no jitter configured
      sum_us += added / 1000000;
      max_us = std::max(max_us, added / 1000000);
      REQUIRE(c.end >= start);
      REQUIRE(c.end - start < Time::us(period_us));
    }
    INFO(hz << " Hz");
    // Twice the mean, to stay in integers: (P - 1) + 2 x 1500 us.
    CHECK(2 * sum_us == period_us * (period_us - 1 + 2 * 1500));
    CHECK(max_us == period_us - 1 + 1500);
    CHECK(link.name() == "usb_hid");
  }
}

TEST_CASE("USB HID: the random operating system delay adds its mean, within its bound") {
  // Uniform on [0, 0.8 ms]: mean 0.4 ms, standard deviation 0.8/sqrt(12) ms
  // per poll. 250 Hz polls (P = 4 ms), reports every 997 us for 4000 cycles of
  // 4000 us: the wait part has mean (4000 - 1)/2 us exactly as above; the
  // delay part is one draw per poll, about 997/4000 of a draw per report.
  UsbHidParams p;
  p.poll_hz = 250;
  p.poll_clock.phase = Time::zero();
  p.os_delay = Time::us(500);
  p.os_jitter = Time::us(800);
  UsbHidLink link(p, latsim::des::RandomStream(2, "test.usb"));
  const int64_t n = 4000 * 4;  // four full cycles of the wait
  double sum_ms = 0.0, max_ms = 0.0;
  for (int64_t i = 0; i < n; ++i) {
    const Time start = Time::us(997 * i);
    const double added = (link.carry(start).visible - start).to_ms();
    sum_ms += added;
    max_ms = std::max(max_ms, added);
    REQUIRE(added >= 0.5);
  }
  const double expected_ms = (4.0 - 0.001) / 2.0 + 0.5 + 0.4;
  // Reports share their poll's draw: the mean is over about n x 997 / 4000
  // polls' draws, standard error 0.8 / sqrt(12 x polls) ms; allow six.
  const double polls = static_cast<double>(n) * 997.0 / 4000.0;
  const double tol_ms = 6.0 * 0.8 / std::sqrt(12.0 * polls);
  CHECK(sum_ms / static_cast<double>(n) == Approx(expected_ms).margin(tol_ms));
  CHECK(max_ms <= 4.0 + 0.5 + 0.8);  // at most P + delay + the jitter's bound
  CHECK(max_ms > 4.0 + 0.5);         // some report waits most of P and draws more than 1 us of jitter
}

TEST_CASE("USB HID: reports one poll carries reach the application together") {
  UsbHidParams p;
  p.poll_hz = 125;
  p.poll_clock.phase = Time::zero();
  p.os_jitter = Time::ms(2);
  p.os_jitter_shape = UsbHidParams::DelayShape::Exponential;
  UsbHidLink link(p, latsim::des::RandomStream(3, "test.usb"));
  // Three reports inside (0, 8 ms] all cross at the 8 ms poll.
  const Carriage a = link.carry(Time::ms(1)), b = link.carry(Time::ms(4)), c = link.carry(Time::ms(8));
  CHECK(a.end == Time::ms(8));
  CHECK(a.visible == b.visible);
  CHECK(b.visible == c.visible);
  CHECK_THROWS_AS(link.carry(Time::ms(7)), std::logic_error);  // out of order
}
