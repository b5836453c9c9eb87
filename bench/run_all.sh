#!/usr/bin/env bash
# Every comparison in BENCHMARKS.md, in one run on one machine, so that the ratios compare
# like with like. BicycleParameters and PyDy live in throw-away virtual environments under
# /tmp; neither is a dependency of whipple.
#
#   bash bench/run_all.sh 2>&1 | tee /tmp/bench.log
set -euo pipefail
cd "$(dirname "$0")/.."

[ -x /tmp/bpvenv/bin/python ] || { python3 -m venv /tmp/bpvenv && /tmp/bpvenv/bin/pip install -q bicycleparameters; }
[ -x /tmp/pydyvenv/bin/python ] || { python3 -m venv /tmp/pydyvenv && /tmp/pydyvenv/bin/pip install -q pydy sympy numpy scipy cython; }

echo "== machine"; nproc; uptime

echo "== whipple: linear sweep (criterion)"
cargo bench -q -p whipple-bench --bench sweep 2>&1 | grep -E "^linear|^critical|time:|thrpt:"
echo "== BicycleParameters: the same sweep"
/tmp/bpvenv/bin/python bench/bicycleparameters_sweep.py

echo "== whipple: design maps (criterion)"
cargo bench -q -p whipple-bench --bench design 2>&1 | grep -E "^design_map|time:|thrpt:"
cargo build -q --release -p whipple-bench --example design_rate
target/release/examples/design_rate benchmark trail=0:0.2:1000 head_angle_deg=60:80:1000
target/release/examples/design_rate schwinn-crown trail=-0.05:0.25:1000 head_angle_deg=60:85:1000
echo "== BicycleParameters: a design map by eigenvalue scans"
/tmp/bpvenv/bin/python bench/bicycleparameters_design_map.py

echo "== whipple: non-linear model (criterion)"
cargo bench -q -p whipple-bench --bench nonlinear 2>&1 | grep -E "^nonlinear|time:"
if [ -f crates/whipple-bench/benches/linearize.rs ]; then
    echo "== whipple: linearization (criterion)"
    cargo bench -q -p whipple-bench --bench linearize 2>&1 | grep -E "^[a-z]|time:"
fi
echo "== whipple: the rider (criterion)"
cargo bench -q -p whipple-bench --bench rider 2>&1 | grep -E "^rider|time:"
echo "== PyDy: the same motion"
cargo build -q --release -p whipple-cli
/usr/bin/time -f "whipple simulate CLI: %e s wall, %U s user" target/release/whipple simulate \
    --bike benchmark --speed 4.6 --lean-rate 0.5 --duration 10 --format csv --out /tmp/whipple_traj.csv
/tmp/pydyvenv/bin/python bench/pydy_whipple.py /tmp/pydy_traj.csv
/tmp/pydyvenv/bin/python bench/compare_trajectories.py /tmp/pydy_traj.csv /tmp/whipple_traj.csv

echo "== whipple serve: load test"
cargo test -q --release -p whipple-web --test load -- --nocapture 2>&1 | grep -iE "requests|errors|throughput" || true
