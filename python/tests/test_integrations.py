"""Issue 49: `verify --sarif` and `verify --junit` over a folder of programs, validated against the
published schemas copied into tests/data/schemas/: SARIF 2.1.0's JSON Schema (OASIS, from
github.com/oasis-tcs/sarif-spec, sarif-2.1/schema/sarif-schema-2.1.0.json) and the JUnit XML schema
CI servers validate against (Jenkins xUnit's junit-10.xsd, from github.com/jenkinsci/xunit-plugin,
src/main/resources/org/jenkinsci/plugins/xunit/types/model/xsd/junit-10.xsd)."""

import json
import os
import pathlib
import shutil
import subprocess

import jsonschema
import xmlschema

REPO = pathlib.Path(__file__).resolve().parents[2]
SCHEMAS = REPO / "tests" / "data" / "schemas"


def library(tmp_path):
    lib = tmp_path / "lib"
    lib.mkdir()
    shutil.copy(REPO / "tests" / "data" / "whole" / "plate.nc", lib / "plate.nc")
    # The shaft's G76 ending at X21.7 (not X21.423): d2 = 21.7 + (22.701 - 21.546) = 22.855, over
    # 6g's 22.663, whatever the insert (none is named: the full-profile one is assumed).
    shaft = (REPO / "tests" / "data" / "whole" / "shaft.nc").read_text()
    assert "G76 X21.423 " in shaft
    (lib / "shaft.nc").write_text(shaft.replace("G76 X21.423 ", "G76 X21.7 "))
    (lib / "broken.nc").write_text("G0 X10 Z5\nG76 P010060 Q100 R0.05\nG76 X8 Z-10 P1000 Q300 F1.5 G\n")
    return lib


def cli(cwd, *args):
    binary = os.environ.get("THREADCHECK_BIN")
    assert binary, "THREADCHECK_BIN must name the threadcheck binary"
    r = subprocess.run([binary, *args], capture_output=True, text=True, cwd=cwd)
    assert r.returncode == 2, f"the broken program makes the run's worst 2, got {r.returncode}: {r.stderr}"
    return r.stdout


def test_sarif_is_valid_sarif_2_1_0(tmp_path):
    library(tmp_path)
    log = json.loads(cli(tmp_path, "verify", "lib", "--format", "sarif"))
    schema = json.loads((SCHEMAS / "sarif-schema-2.1.0.json").read_text())
    jsonschema.Draft4Validator.check_schema(schema)
    errors = sorted(jsonschema.Draft4Validator(schema).iter_errors(log), key=lambda e: list(e.path))
    assert not errors, [f"{list(e.path)}: {e.message[:200]}" for e in errors]
    # The broken program, the plate's unchecked helices, the shaft's three failing checks (d, d2,
    # the GO gauge) and, as notes, the three its assumed insert alone decides (issue 59).
    levels = [r["level"] for r in log["runs"][0]["results"]]
    assert levels == ["error"] * 5 + ["note"] * 3

def test_junit_is_valid_against_the_junit_schema(tmp_path):
    library(tmp_path)
    xml = cli(tmp_path, "verify", "lib", "--format", "junit")
    schema = xmlschema.XMLSchema(str(SCHEMAS / "junit-10.xsd"))
    errors = list(schema.iter_errors(xml))
    assert not errors, [str(e)[:300] for e in errors]
    suites = schema.to_dict(xml)
    # The broken program's case; the plate's four taps and its helices; the shaft's thread and tap.
    assert (suites["@tests"], suites["@failures"], suites["@errors"]) == ("8", "2", "1")
