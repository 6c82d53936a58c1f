#!/usr/bin/env bash
# lib.sh's DDS domain claim, in a claims folder of this test's own (TMPDIR): two tests at once
# hold two domains; a domain whose claimant has gone is taken over, a live one never; with
# every domain held the test stops saying so; a test's claim goes when it ends.
source "$(dirname "$0")/lib.sh"
export TMPDIR=$WORK/tmp
claims=$TMPDIR/rpsd-test-claims/dds-domain
mkdir -p "$claims"
LIB=$(dirname "$0")/lib.sh

# A test that claims, writes its domain to FILE and holds it until FILE.done appears (60 s at
# most). Run in the background, it is the background job itself (exec): cleanup kills it.
holder() {
  exec bash -c "source '$LIB'; echo \$DOMAIN > '$1'; for _ in \$(seq 1200); do [ -e '$1.done' ] && break; sleep 0.05; done"
}
wait_for() { for _ in $(seq 200); do [ -s "$1" ] && return 0; sleep 0.05; done; fail "no $1"; }

holder "$WORK/a" & PIDS+=($!); a_pid=$!
wait_for "$WORK/a"
holder "$WORK/b" & PIDS+=($!); b_pid=$!
wait_for "$WORK/b"
a=$(cat "$WORK/a") b=$(cat "$WORK/b")
[ "$a" != "$b" ] || fail "two tests at once both hold domain $a"
[ "$a" -ge 1 ] && [ "$a" -le 199 ] && [ "$b" -ge 1 ] && [ "$b" -le 199 ] || fail "domains $a, $b outside 1..199"
touch "$WORK/a.done" "$WORK/b.done"
wait $a_pid $b_pid
[ ! -e "$claims/$a" ] && [ ! -e "$claims/$b" ] || fail "a test's claim stayed after it ended: $(ls "$claims")"

# Every domain held by this live test but one, whose claimant has gone: that one is taken.
bash -c 'exit 0' & gone=$!
wait $gone
for d in $(seq 1 199); do mkdir -p "$claims/$d"; echo $$ > "$claims/$d/pid"; done
echo $gone > "$claims/77/pid"
holder "$WORK/c" & PIDS+=($!); c_pid=$!
wait_for "$WORK/c"
[ "$(cat "$WORK/c")" = 77 ] || fail "took domain $(cat "$WORK/c"), not 77, whose claimant had gone"
touch "$WORK/c.done"
wait $c_pid

# Every domain held by a live test: the claimant stops, naming the folder.
mkdir -p "$claims/77"; echo $$ > "$claims/77/pid"
code=0
bash -c "source '$LIB'" > "$WORK/full.log" 2>&1 || code=$?
[ $code = 1 ] || fail "exit $code with every domain held"
grep -q "all 199 DDS domains under $claims are held by live processes" "$WORK/full.log" \
  || fail "no clear reason: $(cat "$WORK/full.log")"
echo "PASS: domains $a and $b at once, released after; a gone claimant's 77 taken over; none free: exit 1"
