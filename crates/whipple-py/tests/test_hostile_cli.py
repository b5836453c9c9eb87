"""A hostile user's catalogue, run against the real `whipple` binary: about 300 inputs that the
named regression tests do not cover (mutated parameter files in four formats, absurd numbers on
every numeric option). Each run must end by itself with status 0, 1 or 2 (never a panic or a
signal), say why on standard error when it fails, and never print NaN as a result."""

import random
import re
import subprocess

from conftest import DATA

BAD_NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "0", "-0", "1e400", "-1",
               "1e16", "1_0", "0x10", "1,5", "\"text\"", "[]", "true", "", "１", "1e", "+-1",
               "9" * 400]

NAN = re.compile(r"(?<![A-Za-z_])(nan|NaN|NAN)(?![A-Za-z_])")


def check(cli, args, tmp_path):
    done = subprocess.run([cli, *args], capture_output=True, text=True, timeout=120,
                          cwd=tmp_path)
    assert done.returncode in (0, 1, 2), (args, done.returncode, done.stderr[-2000:])
    assert "panicked" not in done.stderr, (args, done.stderr[-2000:])
    if done.returncode == 0:
        assert not NAN.search(done.stdout), (args, done.stdout[:2000])
    else:
        assert done.stderr.strip(), args
    return done.returncode


def mutations(text, rng, count, pattern):
    """`count` copies of a parameter file, each with one value replaced by a bad number, one
    key dropped, or one line repeated."""
    lines = text.splitlines()
    values = [i for i, l in enumerate(lines) if re.match(pattern, l)]
    out = []
    for k in range(count):
        copy = list(lines)
        i = rng.choice(values)
        kind = k % 5
        if kind <= 2:
            key = re.match(pattern, copy[i]).group(1)
            sep = "=" if "=" in copy[i] else ","
            copy[i] = f"{key} {sep} {BAD_NUMBERS[(k // 5) % len(BAD_NUMBERS)]}"
        elif kind == 3:
            del copy[i]
        else:
            copy.insert(i, copy[i])
        out.append("\n".join(copy) + "\n")
    return out


def test_mutated_parameter_files(cli, tmp_path):
    rng = random.Random(20261203)
    toml = subprocess.run([cli, "convert", "--bike", "benchmark", "--to", "toml"],
                          capture_output=True, text=True, check=True).stdout
    crown = subprocess.run([cli, "convert", "--bike", "schwinn-crown", "--to", "m",
                            "--keep-form"], capture_output=True, text=True, check=True).stdout
    bp = (DATA / "bicycleparameters" / "FisherBenchmark.txt").read_text()
    cases = [("toml", t) for t in mutations(toml, rng, 60, r"^\s*([A-Za-z_]\w*)\s*=\s*[-0-9]")]
    cases += [("m", t) for t in mutations(crown, rng, 40, r"^\s*([A-Za-z_]\w*)\s*=\s*[-0-9]")]
    cases += [("txt", t) for t in mutations(bp, rng, 60, r"^\s*([A-Za-z]\w*)\s*=")]
    statuses = []
    for k, (ext, text) in enumerate(cases):
        path = tmp_path / f"Mutant{k}Benchmark.{ext}"
        path.write_text(text)
        statuses.append(check(cli, ["speeds", "--bike", str(path)], tmp_path))
        if k % 10 == 0:
            statuses.append(check(cli, ["eig", "--bike", str(path), "--speeds", "0:10:0.5"],
                                  tmp_path))
    # Most are refused, some still describe a bicycle: both outcomes are exercised.
    assert statuses.count(1) > 50 and statuses.count(0) > 5, statuses


ABSURD = ["0", "-0", "-1", "1e-300", "1e300", "nan", "inf", "-inf", "1e16", "abc", "", "1e4",
          "3.5e-324", "0x1p3", "1e-9"]


def test_absurd_numbers_on_every_option(cli, tmp_path):
    runs = []
    for x in ABSURD:
        runs += [
            ["eig", "--bike", "benchmark", "--speeds", f"0:{x}:1"],
            ["eig", "--bike", "benchmark", "--speeds", f"0:10:{x}"],
            ["modes", "--bike", "benchmark", "--speed", x],
            ["speeds", "--bike", "schwinn-crown", "--range", f"{x}:20"],
            ["speeds", "--bike", "benchmark", "--range", f"0:{x}"],
            ["simulate", "--bike", "benchmark", "--speed", x, "--duration", "0.05"],
            ["simulate", "--bike", "benchmark", "--speed", "5", "--duration", "0.05",
             "--dt", x],
            ["simulate", "--bike", "benchmark", "--speed", "5", "--duration",
             "1000" if x == "1e4" else x, "--dt", "0.01", "--every", "1000"],
            ["turn", "--bike", "benchmark", "--speed", "5", "--radius", x],
            ["turn", "--bike", "benchmark", "--speed", x, "--lean-deg", "10"],
            ["map", "--bike", "benchmark", "--x", f"trail=0:{x}:3", "--y", "w=1:1.1:3"],
            ["study", "--bike", "benchmark", "--vary", f"head_angle_deg={x}:80:4"],
            ["sensitivity", "--bike", "benchmark", "--speed", x],
            ["matrices", "--bike", "benchmark", "--speed", x],
            ["validate", "--bike", "benchmark", "--speeds", f"{x}:5:1"],
        ]
    for args in runs:
        check(cli, args, tmp_path)
    assert len(runs) >= 190
