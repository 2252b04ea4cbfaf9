#!/usr/bin/env bash
# A corpus captured inside ODE replays the solves made there: ode-bpp-demo --capture records, per
# island, the warm start the hook solved it from (metadata warm_start and ordering,
# docs/mlcp-format.md), and ode-bpp-solve --warm starts from it. On the winch, whose chain-drum
# contacts keep their index sets from step to step, every captured island then takes exactly the
# pivot steps it took inside ODE (the demo's --csv), while cold solves of the same files take
# other counts; --warm-states takes the index set alone (the ordering chosen afresh). A file whose
# warm start does not fit its rows is an error that names the key.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"
demo=$ODE_BPP_BINARY_DIR/demos/ode-bpp-demo
solve=$ODE_BPP_BINARY_DIR/ode_bpp/ode-bpp-solve
[[ -x "$demo" && -x "$solve" ]] || fail "no $demo or $solve"

capture winch "$demo" winch --seconds 2 --quiet --cond-every 0 --capture "$WORK/corpus" --capture-every 15 \
    --csv "$WORK/inside.csv"
(( STATUS == 0 )) || { show winch; fail "ode-bpp-demo winch --capture: status $STATUS"; }
grep -aq 'warm_start=' "$WORK"/corpus/*.mlcp || fail "no captured file records a warm start"

capture warm "$solve" --methods bpp --warm --csv "$WORK/warm.csv" "$WORK/corpus"
(( STATUS == 0 )) || { show warm; fail "ode-bpp-solve --warm: status $STATUS"; }
capture cold "$solve" --methods bpp --csv "$WORK/cold.csv" "$WORK/corpus"
(( STATUS == 0 )) || { show cold; fail "ode-bpp-solve (cold): status $STATUS"; }
capture states "$solve" --methods bpp --warm-states --csv "$WORK/states.csv" "$WORK/corpus"
(( STATUS == 0 )) || { show states; fail "ode-bpp-solve --warm-states: status $STATUS"; }

# pivots per captured island: inside ODE (step, island) against the replays (file name)
python3 - "$WORK" <<'EOF' || fail "the warm replay does not reproduce the solves inside ODE"
import csv, glob, re, sys
work = sys.argv[1]
inside = {(int(r['step']), int(r['island'])): int(r['pivots']) for r in csv.DictReader(open(f'{work}/inside.csv'))}
def replayed(name):
    out = {}
    for r in csv.DictReader(open(f'{work}/{name}.csv')):
        m = re.search(r'-s(\d+)-i(\d+)\.mlcp$', r['file'])
        out[(int(m.group(1)), int(m.group(2)))] = int(r['pivots'])
    return out
warm, cold, states = replayed('warm'), replayed('cold'), replayed('states')
if not warm:
    sys.exit('no file replayed')
wrong = [(k, warm[k], inside.get(k)) for k in sorted(warm) if warm[k] != inside.get(k)]
if wrong:
    sys.exit(f'{len(wrong)} of {len(warm)} islands: (step, island), pivots replayed, inside ODE: {wrong[:5]}')
if all(cold[k] == warm[k] for k in warm):
    sys.exit('every cold solve took the warm one\'s pivots: the corpus cannot tell a warm start from none')
# --warm-states drops the recorded ordering only: where none was recorded it is --warm
unordered = [k for k in warm if not any(b'ordering=' in open(f, 'rb').read()
                                        for f in glob.glob(f'{work}/corpus/*-s{k[0]:06d}-i{k[1]:02d}.mlcp'))]
if not unordered:
    sys.exit('no captured island without a recorded ordering')
if any(states[k] != warm[k] for k in unordered):
    sys.exit('--warm-states does not start from the recorded index set')
print(f'{len(warm)} islands replayed with the pivots taken inside ODE')
EOF

# a warm start of the wrong length: a read error naming the key, status 1
first=
for f in "$WORK"/corpus/*.mlcp; do grep -aq 'warm_start=' "$f" && { first=$f; break; }; done
python3 - "$first" "$WORK/bad.mlcp" <<'EOF'
import struct, sys, zlib
data = bytearray(open(sys.argv[1], 'rb').read()[:-4])
start = data.index(b'warm_start=') + len(b'warm_start=')
data[start:start] = b'F'  # one row too many
meta_bytes = struct.unpack_from('<I', data, 35)[0] + 1
struct.pack_into('<I', data, 35, meta_bytes)
open(sys.argv[2], 'wb').write(bytes(data) + struct.pack('<I', zlib.crc32(bytes(data))))
EOF
capture bad "$solve" --methods bpp --warm "$WORK/bad.mlcp"
(( STATUS == 1 )) || { show bad; fail "a warm start of n + 1 rows: status $STATUS, expected 1"; }
grep -q "warm_start has .* rows, n = " "$WORK/bad.err" || { show bad; fail "no message naming warm_start"; }
