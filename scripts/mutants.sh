#!/usr/bin/env bash
# The mutant check: how strong is the test suite? Each line of tests/mutants/mutants.tsv is a
# plausible one-line bug. The tree is copied once (without build folders or .git) and built
# once (Release); then, one mutant at a time, the line is replaced in the copy, the mutant's
# build target is rebuilt incrementally and the tests that cover it run (ctest -R). A mutant
# is caught when its tests fail (or it does not build), survived when they pass. The copy's
# file is restored before the next one. Prints caught/survived per mutant, the score and the
# time. Not run by CI (docs/testing.md); run it after changing a rule or its tests.
#
#   scripts/mutants.sh [LIST]     (default tests/mutants/mutants.tsv)
#   RBSF_MUTANT_DIR=/path         the copy and its build (default /tmp/rbsf-mutants)
#
# Refuses the whole list (exit 2) when a mutant's line is no longer in the code, whole and
# once, so the list stays current. Exit 0 when every mutant is caught, 1 when one survives.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
list="${1:-$root/tests/mutants/mutants.tsv}"
work="${RBSF_MUTANT_DIR:-/tmp/rbsf-mutants}"
jobs="$(nproc 2>/dev/null || echo 2)"
started=$(date +%s)

# Every line must still be in the code before anything is built.
stale=0
while IFS=$'\t' read -r file target tests original mutant what; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  count=$(grep -cxF -- "$original" "$root/$file" || true)
  if [[ "$count" != 1 ]]; then
    echo "mutants: $file: the line of '$what' is no longer in the code once (found $count times):" >&2
    echo "  $original" >&2
    stale=1
  fi
done <"$list"
[[ $stale == 0 ]] || exit 2

echo "mutants: copying the tree to $work and building it (Release)"
# Only files whose content changed are copied, each with a fresh time stamp: an object built
# after a source's old time stamp must not pass for up to date.
rm -rf "$work/stage" && mkdir -p "$work/stage" "$work/src"
(cd "$root" && tar --exclude='./build*' --exclude=./.git -cf - .) | tar -xf - -C "$work/stage"
(cd "$work/stage" && find . -type f) | while IFS= read -r f; do
  if ! cmp -s "$work/stage/$f" "$work/src/$f"; then
    mkdir -p "$(dirname "$work/src/$f")"
    cp "$work/stage/$f" "$work/src/$f"
  fi
done
cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DRBSF_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$work/build" -j "$jobs" >/dev/null

# Replace the exact line `original` of file $1 with `mutant` (bash, no interpretation).
mutate() {
  local path="$1" original="$2" mutant="$3" line out=""
  while IFS= read -r line || [[ -n "$line" ]]; do
    if [[ "$line" == "$original" ]]; then out+="$mutant"$'\n'; else out+="$line"$'\n'; fi
  done <"$path"
  printf '%s' "$out" >"$path"
}

caught=0 total=0
while IFS=$'\t' read -r file target tests original mutant what <&3; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  total=$((total + 1))
  t0=$(date +%s)
  mutate "$work/src/$file" "$original" "$mutant"
  if ! cmake --build "$work/build" -j "$jobs" --target "$target" >"$work/build.log" 2>&1; then
    verdict="caught (does not build)"
  elif ctest --test-dir "$work/build" -N -R "$tests" | grep -q "^Total Tests: 0"; then
    verdict="SURVIVED (no test matches)"
  elif ctest --test-dir "$work/build" -R "$tests" -j "$jobs" --timeout 900 >"$work/test.log" 2>&1; then
    verdict="SURVIVED"
  else
    verdict="caught"
  fi
  [[ "$verdict" == caught* ]] && caught=$((caught + 1))
  cp "$work/stage/$file" "$work/src/$file"
  printf '%-24s %-44s %s (%ss; tests: %s)\n' "$verdict" "$what" "$file" \
    "$(($(date +%s) - t0))" "$tests"
done 3<"$list"
# Leave the copy's build as the code is, for the next run.
cmake --build "$work/build" -j "$jobs" >/dev/null
echo "mutants: $caught of $total caught ($((100 * caught / total)) %) in $(($(date +%s) - started)) s"
[[ $caught == "$total" ]]
