#!/usr/bin/env bash
# The Python readers' fuzzer is deterministic: the same seed and number of
# executions keep the same inputs, twice over, and another seed keeps others.
#   same_corpus_twice.sh LATSIM SOURCE_DIR WORK_DIR
set -euo pipefail
latsim=$1 source=$2 work=$3
fuzz() { /usr/bin/python3 "$source/tests/fuzz/python/fuzz_readers.py" "$latsim" "$source" "$work/$1" \
           --target compare --seconds 3600 --runs 60 --seed "$2" --corpus-digest | sed -n 's/^fuzz: corpus digest //p'; }
first=$(fuzz a 7) second=$(fuzz b 7) other=$(fuzz c 8)
echo "seed 7: $first, again: $second; seed 8: $other"
[ -n "$first" ] && [ "$first" = "$second" ] && [ "$first" != "$other" ]
