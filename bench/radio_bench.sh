#!/bin/sh
# The radio link against ns-3's Wi-Fi model on the same traffic: builds
# bench/radio_link_ns3.cpp against Debian's ns-3 (apt-get install
# libns3-dev), runs it and build/radio_link (latsim's model, built by
# `cmake --build build --target radio_link`) at each background load, and
# prints one line per program and load (BENCHMARKS.md, "Radio link").
#   RADIO_LINK=build/radio_link DURATION=10 bench/radio_bench.sh
set -eu
here=$(cd "$(dirname "$0")" && pwd)
latsim=${RADIO_LINK:-build/radio_link}
duration=${DURATION:-10}
work=${WORK:-$(mktemp -d)}
peer="$work/radio_link_ns3"
if [ ! -x "$peer" ]; then
  g++ -std=c++17 -O2 "$here/radio_link_ns3.cpp" -o "$peer" -lns3-wifi -lns3-mobility -lns3-network -lns3-core \
    -lns3-propagation -lns3-spectrum -lns3-antenna -lns3-energy
fi
for load in "0 0" "1 25" "1 50" "1 100"; do
  set -- $load
  echo "== background stations $1, $2 Mb/s"
  printf 'ns-3   '; "$peer" --duration="$duration" --bg-stations="$1" --bg-mbps="$2"
  printf 'latsim '; "$latsim" --duration="$duration" --bg-stations="$1" --bg-mbps="$2" 2>/dev/null
done
