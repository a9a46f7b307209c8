"""Every command's JSON, from the CLI and from the Python package, against the JSON Schema in
docs/json-schema.json. The schema forbids keys it does not list, so a key added to the output
without being documented fails here. THREADCHECK_BIN names the CLI (.ci/run sets it)."""

import json
import os
import pathlib
import subprocess

import jsonschema
import pytest
from referencing import Registry, Resource

import threadcheck

REPO = pathlib.Path(__file__).resolve().parents[2]
SCHEMA = json.loads((REPO / "docs" / "json-schema.json").read_text())
REGISTRY = Registry().with_resource("threadcheck-json", Resource.from_contents(SCHEMA))
PROGRAMS = REPO / "tests" / "data" / "programs"


def validate(command, instance):
    v = jsonschema.Draft202012Validator({"$ref": "threadcheck-json#/$defs/command_" + command},
                                        registry=REGISTRY)
    error = jsonschema.exceptions.best_match(v.iter_errors(instance))
    assert error is None, f"{list(error.absolute_path)}: {error.message[:300]}"


def cli(*args, ok=(0, 1)):
    binary = os.environ.get("THREADCHECK_BIN")
    assert binary, "THREADCHECK_BIN must name the threadcheck binary"
    r = subprocess.run([binary, *args], capture_output=True, text=True, cwd=REPO)
    assert r.returncode in ok, f"exit {r.returncode}: {r.stderr}"
    return r.stdout


def test_the_schema_is_a_valid_schema():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("args", [
    ["--thread", "M10x1.5-6g"],
    ["--thread", "M10x1.5-6H", "--insert", "full"],
    ["--thread", "1/4-20 UNC-2A", "--insert", "full"],
    ["--thread", "Tr20x4-7e", "--insert", "full"],
    ["--thread", "M20x2.5-6g", "--gauge-only", "--no-pass-metrics"],
    ["--thread", "M20x1.5-6g", "--thread", "M40x1.5-6g", "--insert", "full",
     "--program", str(PROGRAMS / "source-docs" / "seed003-two-threads.nc")],
    ["--thread", "M20x1.5-6g", "--program", str(PROGRAMS / "fanuc-runout-shoulder.nc"),
     "--machine", "training-lathe", "--clearance-angle", "1"],
    ["--thread", "M10x1.5-6g", "--program", str(PROGRAMS / "fanuc-g92-above-blank.nc")],
    ["--thread", "1/2-14 NPT", "--program", str(PROGRAMS / "fanuc-g92-npt-1-2.nc"), "--insert", "full"],
    ["--thread", "M20x1.5-6g", "--program", str(PROGRAMS / "heidenhain-g31-g33.nc"), "--dialect", "heidenhain"],
    ["--thread", "M20x1.5-6g", "--program", str(PROGRAMS / "mitsubishi-g76.nc"), "--dialect", "mitsubishi"],
    ["--thread", "M20x1.5-6g", "--program", str(PROGRAMS / "okuma-g33-repeats.min")],
    ["--thread", "M24xPh3P1.5-6g", "--program", str(PROGRAMS / "sinumerik-cycle99-two-start.mpf")],
    # The thread named by the program: two operations by a comment, one inferred.
    ["--program", str(PROGRAMS.parent / "naming" / "fanuc-two-threads.nc")],
    # Every thread a program makes: turned and tapped; tapped and milled; milled not checked.
    ["--program", str(PROGRAMS.parent / "whole" / "shaft.nc"), "--insert", "full"],
    ["--program", str(PROGRAMS.parent / "whole" / "plate.nc"), "--tools", str(PROGRAMS.parent / "whole" / "plate-tools.toml")],
    ["--program", str(PROGRAMS.parent / "whole" / "plate.nc")],
    # A correction with an earlier pass deeper than its new value (`deeper`).
    ["--thread", "M12x1.75-6g", "--program", str(PROGRAMS / "shop" / "partial-insert-m12.nc"), "--insert", "full"],
])
def test_verify(args):
    validate("verify", json.loads(cli("verify", *args, "--json", "-")))


@pytest.mark.parametrize("designation", ["M10x1.5-6g", "M10x1.5-6H/6g", "1/4-20 UNC-2A", "Tr40x7-7H",
                                         "1-5 ACME-2G", "1/2-14 NPT", "G1/2A", "BSF 3/8 medium"])
def test_limits(designation):
    validate("limits", json.loads(cli("limits", designation, "--json", ok=(0,))))
    validate("limits", threadcheck.limits(designation))


@pytest.mark.parametrize("args", [
    ["--thread", "M10x1.5-6g"],
    ["--thread", "M10x1.5-6g", "--final-x", "8.2", "--passes", "4"],
    ["--program", str(PROGRAMS / "fanuc-g32.nc")],
    ["--program", str(PROGRAMS / "fanuc-g32.nc"), "--thread", "M10x1.5-6g"],
    ["--program", str(PROGRAMS / "linuxcnc-g76.ngc"), "--dialect", "linuxcnc"],
])
def test_passes(args):
    validate("passes", json.loads(cli("passes", *args, "--json", ok=(0,))))


def test_compare():
    validate("compare", json.loads(cli("compare", "--thread", "M10x1.5-6g", "--insert", "full", "--json", "-")))


def test_fit():
    validate("fit", json.loads(cli("fit", "--thread", "M10x1.5-6H/6g", "--json", "-")))


@pytest.mark.parametrize("program,dialect,target,diameter", [
    ("boss-chords.nc", "fanuc", "boss.toml", "6"),
    ("cam-normal-offset.nc", "dyna", "cardioid.toml", "6"),
])
def test_mill(program, dialect, target, diameter):
    data = PROGRAMS.parent
    out = cli("mill", "--program", str(PROGRAMS / "milling" / program), "--dialect", dialect,
              "--target", str(data / "targets" / target), "--tool-diameter", diameter, "--json", ok=(0, 1))
    validate("mill", json.loads(out))


def test_sweep_lines():
    out = cli("sweep", "--min-d", "10", "--max-d", "12", "--series", "coarse", "--infeed", "radial",
              "--schedule", "constant-area", "--json")
    lines = [json.loads(line) for line in out.splitlines() if line.strip()]
    assert len(lines) >= 4
    for line in lines:
        validate("sweep_line", line)


def test_python_dicts():
    g76 = "G0 X22 Z5\nG76 P010060 Q100 R0.02\nG76 X18.2 Z-20 P900 Q300 F1.5\n"
    validate("verify", threadcheck.verify("M20x1.5-6g", program=g76, insert="full"))
    validate("verify", threadcheck.verify("M10x1.5-6g", final_x=8.2))
    validate("passes", threadcheck.passes(program=g76))
    validate("passes", threadcheck.passes("M10x1.5-6g"))


@pytest.mark.parametrize("args", [
    ["--thread", "M10x1.5-6g", "--insert", "full", "--measured-m", "10.32", "--wire", "0.866"],
    ["--thread", "M10x1.5-6g", "--measured-d2", "8.95"],
    ["--thread", "M10x1.5-6H", "--gauge", "go-fails"],
    ["--thread", "M10x1.5-6g", "--insert", "full", "--program", str(PROGRAMS / "m10-g92-radial.nc"),
     "--measured-d2", "9.02", "--pickup-z", "0.25"],
    ["--thread", "1/4-20 UNC-2A", "--coating", "0.005", "--gauge", "ok"],
])
def test_correct(args):
    validate("correct", json.loads(cli("correct", *args, "--json", "-")))


@pytest.mark.parametrize("args", [
    ["--thread", "M10x1.5-6g", "--x-sigma", "0.01", "--samples", "300"],
    ["--thread", "M10x1.5-6H", "--insert", "partial:0.05", "--tip-radius-tol", "0.01",
     "--wear-per-part", "0.001", "--samples", "300"],
    ["--thread", "M10x1.5-6g", "--insert", "full", "--program", str(PROGRAMS / "m10-g92-radial.nc"),
     "--samples", "50"],
])
def test_capability(args):
    validate("capability", json.loads(cli("capability", *args, "--json", "-")))
    validate("capability", threadcheck.capability("M10x1.5-6g", x_sigma=0.004, samples=100))
    validate("correct", threadcheck.correct("M10x1.5-6g", measured_d2=9.0))


def test_python_fit_compare_mill_match_the_schema():
    validate("fit", threadcheck.fit("M10x1.5-6H/6g"))
    validate("compare", threadcheck.compare("M10x1.5-6g", insert="full"))
    prog = (PROGRAMS / "milling" / "boss-chords.nc").read_text()
    target = (PROGRAMS.parent / "targets" / "boss.toml").read_text()
    validate("mill", threadcheck.mill(prog, target, 6.0))


def test_tap():
    tapping = PROGRAMS / "tapping"
    validate("tap", json.loads(cli("tap", "--program", str(tapping / "m10-g84.nc"), "--tools",
                                   str(tapping / "tools-80.toml"), "--json", "-")))
    text = (tapping / "m10-g84.nc").read_text()
    validate("tap", threadcheck.tap(text, (tapping / "tools-85.toml").read_text()))


def test_thread_mill():
    mill = PROGRAMS / "threadmill"
    validate("thread_mill", json.loads(cli("thread-mill", "--program", str(mill / "m20-dc14.nc"), "--thread",
                                           "M20x1.5-6H", "--cutter-diameter", "14", "--json", "-")))
    validate("thread_mill", threadcheck.thread_mill((mill / "m20-dc6.nc").read_text(), "M20x1.5-6H", 6.0))
    # A multi-form cutter: its rows and row pitch, and the row_pitch check.
    validate("thread_mill", threadcheck.thread_mill((mill / "m20-dc14-rows8.nc").read_text(), "M20x1.5-6H", 14.0,
                                                    cutter_rows=8, cutter_row_pitch=1.5))
    # A taper thread: its helices' radius_change, the gauge plane and taper checks.
    validate("thread_mill", threadcheck.thread_mill((mill / "npt-half-internal.nc").read_text(), cutter_diameter=10.0))


def test_tap_sinumerik():
    tapping = PROGRAMS / "tapping"
    validate("tap", threadcheck.tap((tapping / "m10-cycle84.mpf").read_text(), (tapping / "tools-85.toml").read_text(),
                                    dialect="sinumerik"))
