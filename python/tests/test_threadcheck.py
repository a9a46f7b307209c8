"""Tests of the Python package against values from outside the code: ISO 965-1's tables, the
G76 sheet's stated result, and pass depths derived by hand. THREADCHECK_BIN names the CLI binary
the dicts are compared with (.ci/run sets it); without it that test fails, it does not skip."""

import json
import re
import math
import os
import pathlib
import subprocess
import tempfile

import pytest

import threadcheck

# A two-block Fanuc G76 of our own for M20x1.5: thread height P900 (0.9 mm) from X20.0 to the
# final X18.2, first depth Q300, finishing allowance R0.02, 60° insert.
G76_M20 = """%
O2001 (M20X1.5 POST OUTPUT)
G21 G40 G97 S500 M03
T0101
G0 X22.0 Z5.0
G76 P010060 Q100 R0.02
G76 X18.2 Z-20.0 P900 Q300 F1.5
G0 X100.0 Z100.0
M30
%
"""


def test_limits_match_iso_965_1():
    # ISO 965-1, M10x1.5-6g: d2 8.994/8.862, d 9.968/9.732 (es = -32 µm).
    lim = threadcheck.limits("M10x1.5-6g")
    ext = lim["external"]
    assert ext["pitch_diameter"] == {"max": 8.994, "min": 8.862}
    assert ext["major_diameter"] == {"max": 9.968, "min": 9.732}
    assert lim["internal"] is None
    # 6H: D2 9.026/9.206, D1 8.376/8.676.
    nut = threadcheck.limits("M10x1.5-6H")["internal"]
    assert nut["pitch_diameter"] == {"max": 9.206, "min": 9.026}
    assert nut["minor_diameter"] == {"max": 8.676, "min": 8.376}


def test_verify_program_text_reads_72_um_over_6g():
    # A full-profile insert's tip sits at d3, so the cut d2 = X + (d2 - d3) = 18.2 + 0.57735·P
    # = 19.0660; 6g's d2 max is 19.026 - 0.032 = 18.994: 72.0 µm over (the G76 sheet's result).
    r = threadcheck.verify("M20x1.5-6g", program=G76_M20, insert="full")
    assert r["verdict"] == "fail"
    (op,) = r["operations"]
    d2 = next(c for c in op["checks"] if c["feature"] == "pitch_diameter")
    assert abs(d2["deviation_um"] - 72.0) < 0.5
    # The correction a post applies: the suggested X brings d2 into the tolerance.
    x = op["suggested_final_x"]
    fixed = threadcheck.verify("M20x1.5-6g", program=G76_M20.replace("X18.2", "X%.4f" % x), insert="full")
    assert fixed["verdict"] == "pass"


def test_pasted_text_is_read_as_a_file_is_with_its_dos_end_of_file():
    # Issue 58: a trailing ^Z (DOS end of file) ends the text on every route, as it does when the
    # command line reads a file; a NUL byte is refused at its place.
    plain = threadcheck.verify("M20x1.5-6g", program=G76_M20, insert="full")
    with_eof = threadcheck.verify("M20x1.5-6g", program=G76_M20 + "\x1a", insert="full")
    assert with_eof["verdict"] == plain["verdict"]
    assert with_eof["operations"][0]["passes"] == plain["operations"][0]["passes"]
    with pytest.raises(ValueError, match=r"^post\.nc:1:3: a NUL byte"):
        threadcheck.verify("M20x1.5-6g", program="G0\x00X1\n", program_name="post.nc")


def test_a_designation_of_another_size_is_refused_naming_both():
    # Issue 59: an M30x1.5 bolt (G76 to X28.16 = 30 - 2 x 0.920) given M20x1.5-6g (d3 18.160):
    # refused at the G76's second block, naming both diameters, never corrected.
    bolt = "G21 G18 G99\nT0101\nG97 S800 M3\nG0 X31 Z2\nG1 X29.85 F0.2\nG1 Z-25\nG0 X32 Z5\n" \
        "G76 P010060 Q100 R0.05\nG76 X28.16 Z-20 P920 Q350 F1.5\nM30\n"
    with pytest.raises(ValueError, match=r"^m30\.nc:9:1: G76: the passes cut about Ø30\.0 .*M20x1\.5-6g is Ø20 \(d3 18\.160\)"):
        threadcheck.verify("M20x1.5-6g", program=bolt, program_name="m30.nc")


def as_keys(cli_text):
    """The command line's text with each flag (``--gcode-system``) written as the keyword Python
    takes (``gcode_system``): the one way Python's words differ from the command line's."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), cli_text)


def test_dicts_are_the_cli_json():
    binary = os.environ.get("THREADCHECK_BIN")
    assert binary, "no threadcheck binary: build it (cargo build --release), put it on the PATH, or name it in THREADCHECK_BIN"
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "m20.nc")
        with open(path, "w") as f:
            f.write(G76_M20)
        cli = subprocess.run([binary, "verify", "--thread", "M20x1.5-6g", "--program", path, "--dialect", "fanuc",
                              "--insert", "full", "--json", "-"], capture_output=True, text=True)
        assert cli.returncode == 1, cli.stderr
        py = threadcheck.verify("M20x1.5-6g", program=G76_M20, insert="full", program_name=path, dialect="fanuc")
        assert py == json.loads(as_keys(cli.stdout))
        cli = subprocess.run([binary, "limits", "M12x1.25-6H", "--json"], capture_output=True, text=True)
        assert cli.returncode == 0, cli.stderr
        assert threadcheck.limits("M12x1.25-6H") == json.loads(cli.stdout)
        cli = subprocess.run([binary, "passes", "--program", path, "--dialect", "fanuc", "--json"],
                             capture_output=True, text=True)
        assert cli.returncode == 0, cli.stderr
        assert threadcheck.passes(program=G76_M20, program_name=path, dialect="fanuc") == json.loads(as_keys(cli.stdout))


def test_passes_of_a_plan_are_constant_area():
    # Radial infeed, 4 passes from X10 to X8.2: depth 0.9·sqrt(i/4), X = 10 - 1.8·sqrt(i/4).
    p = threadcheck.passes("M10x1.5-6g", final_x=8.2, passes=4, infeed="radial", blank_diameter=10.0)
    xs = [q["x_end"] for q in p["passes"]]
    assert len(xs) == 4
    for i, x in enumerate(xs, start=1):
        assert math.isclose(x, 10.0 - 1.8 * math.sqrt(i / 4), abs_tol=1e-9)


def test_passes_of_program_text():
    p = threadcheck.passes(program=G76_M20)
    (op,) = p["operations"]
    assert op["cycle"].startswith("G76") and op["source_line"] == 7
    assert op["passes"][-1]["x_end"] == pytest.approx(18.2, abs=1e-9)
    assert all(q["z_end"] == -20.0 and q["lead"] == 1.5 for q in op["passes"])


def test_infeed_words_are_the_cli_words():
    # Half of 60° less 0.5° is 29.5°; flank:27 is 27° whatever the form.
    assert threadcheck.verify("M10x1.5-6g", infeed="modified")["plan"]["infeed"]["angle"] == 29.5
    assert threadcheck.verify("M10x1.5-6g", infeed="flank:27")["plan"]["infeed"]["angle"] == 27.0
    with pytest.raises(ValueError, match="expected radial, flank"):
        threadcheck.verify("M10x1.5-6g", infeed="sideways")


def test_errors_are_value_errors_with_the_place():
    bad = G76_M20.replace("G76 X18.2", "G76.1 X18.2")
    with pytest.raises(ValueError, match=r"^post\.nc:7:\d+: .*G76\.1"):
        threadcheck.verify("M20x1.5-6g", program=bad, program_name="post.nc")
    with pytest.raises(ValueError, match="M10x1.5-6q"):
        threadcheck.limits("M10x1.5-6q")
    with pytest.raises(ValueError, match="at least one pass"):
        threadcheck.passes("M10x1.5-6g", passes=0)
    with pytest.raises(ValueError, match="dialect 'hurco' is not supported"):
        threadcheck.verify("M20x1.5-6g", program=G76_M20, dialect="hurco")


HEIDENHAIN_G31 = """MACHINING
N1 G95 F0.2 G97 S800 M3
N2 G0 X22 Z5
[V1: four equal infeeds of 0.23 to U 0.92; the last at X20 - 2*0.92 = 18.16]
N3 G31 X20 Z-20 F1.5 U-0.92 I0.3 V1 B0 P0
END
"""


def test_heidenhain_g31_from_python():
    # The last cut at X18.16 with a full-profile insert: d2 = 18.16 + 0.866025 = 19.026, 32.0 µm
    # over 6g's 18.994 (ISO 965-2).
    passes = threadcheck.passes(program=HEIDENHAIN_G31, dialect="heidenhain")
    assert [p["x_end"] for p in passes["passes"]] == pytest.approx([19.54, 19.08, 18.62, 18.16])
    v = threadcheck.verify("M20x1.5-6g", program=HEIDENHAIN_G31, dialect="heidenhain", insert="full")
    d2 = next(c for c in v["operations"][0]["checks"] if c["feature"] == "pitch_diameter")
    assert d2["deviation_um"] == pytest.approx(32.0, abs=0.1)


SINUMERIK_CYCLE99 = """G18 G90 G71 DIAMON
G97 S800 M3
G0 X24 Z5
CYCLE99(0,20,-25,,3,2,0.92,0.05,30,0,3,0,1.5,100101,1)
M30
"""


def test_sinumerik_cycle99_from_python():
    # The named order (docs/dialects.md): TDEP 0.92 - FAL 0.05 = 0.87 in NRC 3 linear cuts (VARI
    # units 1), then 0.92: X = 20 - 2 * depth; roughing and finishing (hundred-thousands 1 is
    # roughing only: the cuts stop at 0.87).
    passes = threadcheck.passes(program=SINUMERIK_CYCLE99, dialect="sinumerik")
    assert [p["x_end"] for p in passes["passes"]] == pytest.approx([19.42, 18.84, 18.26])
    both = SINUMERIK_CYCLE99.replace("100101", "300101")
    passes = threadcheck.passes(program=both, dialect="sinumerik")
    assert [p["x_end"] for p in passes["passes"]] == pytest.approx([19.42, 18.84, 18.26, 18.16])
    v = threadcheck.verify("M20x1.5-6g", program=both, dialect="sinumerik", insert="full")
    d2 = next(c for c in v["operations"][0]["checks"] if c["feature"] == "pitch_diameter")
    assert d2["deviation_um"] == pytest.approx(32.0, abs=0.1)
    assert "CYCLE99 read as (SPL, DM1, FPL" in str(v["notes"])
    # DM2 left empty: a cylindrical thread, DM2 = DM1 (a named default, said).
    assert "CYCLE99 DM2 empty: read as DM1" in str(v["notes"])


def test_a_shallower_correction_names_the_deeper_passes():
    # M12x1.75-6g (ISO 965-2: d2 10.679-10.829) with a full-profile insert: d2 = X + 1.010363.
    # The run ends at X9.6: the correction is X9.744 (d2 10.754, the middle), and the X9.7 before
    # it cuts deeper than that, so it is named to be set to X9.744 too.
    run = "G21 G97 S600 M3\nG0 X14 Z4\nG92 X11.4 Z-20 F1.75\nX10.6\nX10.0\nX9.7\nX9.6\nG0 X50 Z50\nM30\n"
    v = threadcheck.verify("M12x1.75-6g", program=run, dialect="fanuc", insert="full")
    c = v["operations"][0]["correction"]
    assert (c["line"], c["value"]) == (7, pytest.approx(9.744))
    assert [(d["line"], d["written"]) for d in c["deeper"]] == [(6, "X9.7")]


def test_correct_takes_one_operation_of_a_program_of_several():
    # Our DIN program's three M20x1.5 operations each cut d2 19.026 (full-profile insert); the
    # part of operation 2 measures 19.066: to 6g's middle 18.924 its depth U-0.92 goes to U-0.991.
    program = (pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "programs" / "heidenhain-g31-g33.nc").read_text()
    with pytest.raises(ValueError, match="say which one with operation 1 to 3"):
        threadcheck.correct("M20x1.5-6g", program=program, dialect="heidenhain", insert="full", measured_d2=19.066)
    r = threadcheck.correct("M20x1.5-6g", program=program, dialect="heidenhain", insert="full",
                            measured_d2=19.066, operation=2)
    assert (r["correction"]["line"], r["correction"]["value"]) == (18, pytest.approx(-0.991))
    v = threadcheck.verify("M20x1.5-6g", program=program, dialect="heidenhain", insert="full", operation=3)
    assert [op["operation"]["index"] for op in v["operations"]] == [3]


def test_module_docstring_example_runs():
    import doctest

    failures, tried = doctest.testmod(threadcheck)
    assert tried >= 2 and failures == 0


TWO_PROGRAMS = """O3102
G0 X14 Z4
G92 X11.4 Z-20 F1.75
X10.6
X9.853
G0 X50 Z50
M99
O3101
G21 G97 S600 M3
T0505
M98 P3102
M30
"""


def test_main_and_default_units_reach_the_reader():
    # O3101 calls O3102: it is the main program, and the note says so; --main picks the other.
    p = threadcheck.passes(program=TWO_PROGRAMS, program_name="two.nc")
    assert [q["x_end"] for q in p["passes"]] == [11.4, 10.6, 9.853]
    assert any("O3101 is the main program" in n for n in p["notes"])
    assert p["operations"][0]["tool"] == 5
    p = threadcheck.passes(program=TWO_PROGRAMS, program_name="two.nc", main="O3102")
    assert p["operations"][0]["tool"] is None
    # A program without G20/G21 read as an inch control's: X0.4 in is 10.16 mm.
    inch = threadcheck.passes(program="G0 X0.6 Z0.2\nG92 X0.4 Z-1 F0.0769\nM30\n", default_units="inch")
    assert abs(inch["passes"][0]["x_end"] - 10.16) < 1e-9
    with pytest.raises(ValueError, match="not an O-program number"):
        threadcheck.passes(program=TWO_PROGRAMS, main="P12")


def test_linuxcnc_release_reaches_the_reader():
    # 1 EQ 1.00005: equal within LinuxCNC's 1e-4 before 2.9.0 (X5, Ø10), not within 1e-6 after
    # (X6, Ø12), as the interpreters compare.
    eq = ("G18 G21 G90 G8 S500 M3\nG0 X12 Z2\no1 if [1 EQ 1.00005]\nG1 X5\no1 else\nG1 X6\n"
          "o1 endif\nG33 Z-10 K1.5\nM2\n")
    old = threadcheck.passes(program=eq, dialect="linuxcnc", linuxcnc_release="before-2.9")
    new = threadcheck.passes(program=eq, dialect="linuxcnc")
    assert old["passes"][0]["x_start"] == 10.0
    assert new["passes"][0]["x_start"] == 12.0
    with pytest.raises(ValueError, match="unknown LinuxCNC release"):
        threadcheck.passes(program=eq, dialect="linuxcnc", linuxcnc_release="2.8")


def test_correct_over_wires_follows_the_standard_formula():
    # A full-profile M10x1.5-6g plan over 0.866 mm wires: straight 60° flanks, so
    # d2 = M − 3w + 0.866025·P + the helix term: the wires ride 1.733 µm higher across the
    # helix than in the axial section (an independent 3-D model's figure, issue 48; the classical
    # −0.75·w·tan² λ gives −1.817 µm).
    m, w, p = 10.32, 0.866, 1.5
    r = threadcheck.correct("M10x1.5-6g", insert="full", measured_m=m, wire=w)
    wires = r["measured"]["over_wires"]
    assert wires["helix_term"] == pytest.approx(-0.001733, abs=5e-6)
    # The classical term at the part's own d2, which the reading gives (issue 64).
    d2 = r["measured"]["pitch_diameter"]
    assert wires["helix_term_classical"] == pytest.approx(-0.75 * w * (p / (math.pi * d2)) ** 2, abs=1e-7)
    assert r["measured"]["pitch_diameter"] == pytest.approx(m - 3 * w + 0.866025404 * p + wires["helix_term"], abs=1e-6)
    assert r["verdict"] == "fail"
    # The correction brings d2 to 8.928, the middle of 8.862–8.994.
    assert r["delta_pitch_diameter"] == pytest.approx(8.928 - r["measured"]["pitch_diameter"], abs=1e-9)
    with pytest.raises(ValueError, match="measured_m and wire go together"):
        threadcheck.correct("M10x1.5-6g", measured_m=10.3)


def test_correct_matches_the_cli_and_a_coating_moves_the_limits():
    out = subprocess.run([os.environ["THREADCHECK_BIN"], "correct", "--thread", "M10x1.5-6g",
                          "--measured-d2", "9.0", "--json"], capture_output=True, text=True)
    assert json.loads(out.stdout) == threadcheck.correct("M10x1.5-6g", measured_d2=9.0)
    # A 10 µm coat on a 60° thread grows d2 by 4t = 40 µm. The standards' rule (the default):
    # ISO 965-1's 8.862–8.994 before coating, the maximum capped at basic 9.026 − 0.040 = 8.986.
    ext = threadcheck.limits("M10x1.5-6g", coating=0.010)["external"]
    assert ext["pitch_diameter"] == {"max": 8.986, "min": 8.862}
    # The class after coating (a drawing that says so): every limit 40 µm down.
    after = threadcheck.limits("M10x1.5-6g", coating=0.010, coating_limits="after")["external"]
    assert after["pitch_diameter"] == {"max": 8.954, "min": 8.822}
    # A rolled M10x1.5-6g: the dies at 6g's middle d2 8.928, the root 2H/3 under it
    # (H = 1.299038), the blank near 8.970 (derived by hand in tests/limits.rs).
    rolled = threadcheck.limits("M10x1.5-6g", rolled=True)["rolled"]
    assert abs(rolled["root_diameter"] - (8.928 - 2 * 1.299038 / 3)) < 1e-6
    assert abs(rolled["blank_for_full_crest"] - 8.970) < 0.003


def test_capability_wear_alone_gives_the_derived_parts_per_edge():
    # Part k carries k parts' wear: from the best X (part 1 on d2 min 8.862) parts stay in
    # while 8.862 + 2(k − 1)w ≤ 8.994: ⌊0.132 / 0.004⌋ + 1 = 34 for w = 2 µm.
    r = threadcheck.capability("M10x1.5-6g", insert="full", wear_per_part=0.002, samples=50)
    assert r["best_parts_per_edge"] == 34
    assert sum(r["histogram"]["counts"]) == 50


def test_fit_compare_and_mill_from_python():
    # Mid-tolerance M10x1.5-6H/6g, full-profile inserts: the flank clearance is
    # (D2 mid − d2 mid)/2 · sin 30° = (9.116 − 8.928)/2 · 0.5 = 47.0 µm.
    f = threadcheck.fit("M10x1.5-6H/6g", bolt_insert="full", nut_insert="full")
    assert f["verdict"] == "fits"
    assert f["clearance_um"] == pytest.approx(47.0, abs=0.1)
    # compare with one infeed and one schedule: one row.
    c = threadcheck.compare("M10x1.5-6g", infeed="radial", schedule="sandvik")
    assert [(s["infeed"], s["schedule"]) for s in c["strategies"]] == [("radial", "sandvik")]
    assert threadcheck.compare("M10x1.5-6g")["recommended"]["infeed"] == "modified 29.5°"
    # A Ø40 boss cut with a Ø6 cutter along 36 chords of the centre circle R = 23: the worst
    # gouge is the chord sag 23·(1 − cos 5°).
    prog = "G0 X23 Y0 Z2\nG1 Z-1\n" + "".join(
        f"G1 X{23 * math.cos(math.radians(10 * k)):.9f} Y{23 * math.sin(math.radians(10 * k)):.9f}\n"
        for k in range(1, 37)) + "G0 Z2\nM30\n"
    target = 'x = "20*cos(t)"\ny = "20*sin(t)"\nt = [0, 360]\nmaterial = "inside"\n'
    m = threadcheck.mill(prog, target, 6.0)
    assert m["gouge_max"] == pytest.approx(23 * (1 - math.cos(math.radians(5))), abs=1e-7)
    with pytest.raises(ValueError, match="exclude each other"):
        threadcheck.fit("M10x1.5-6H/6g", bolt_program="G0 X10\n", bolt_final_x=8.1)


# ---- issue 30: the complete package

# The post-processor guide's pattern, unchanged.
def checked_g76(designation, x_final, program_for):
    report = threadcheck.verify(designation, program=program_for(x_final), insert="full",
                                program_name="post.nc")
    op = report["operations"][0]
    if report["verdict"] != "pass":
        x_final = op["suggested_final_x"]   # d2 in the middle of its tolerance
    return program_for(x_final)


def g76(x, z_end=-20.0):
    return ("G0 X22.0 Z5.0\nG76 P010060 Q100 R0.02\n"
            f"G76 X{x:.3f} Z{z_end:.1f} P900 Q300 F1.5\n")


def test_readme_post_pattern_runs_on_a_form_failing_and_a_no_cut_program():
    # A partial r0.04 insert cannot make 6g's root radius (0.125P = 0.1875 min): the form fails
    # whatever X, even at the X that puts its d2 mid-tolerance; the post still gets a number.
    first = threadcheck.verify("M20x1.5-6g", program=g76(18.2), insert="partial", program_name="post.nc")
    x_mid = round(first["operations"][0]["suggested_final_x"], 3)
    report = threadcheck.verify("M20x1.5-6g", program=g76(x_mid), insert="partial", program_name="post.nc")
    op = report["operations"][0]
    assert not next(c for c in op["checks"] if c["feature"] == "root_radius")["ok"]
    assert report["verdict"] == "fail"
    assert next(c for c in op["checks"] if c["feature"] == "pitch_diameter")["ok"]
    assert isinstance(op["suggested_final_x"], float)
    # No cut: the last pass at X20.2 never reaches the blank (Ø20.1 here); a plan's X is offered.
    nocut = threadcheck.verify("M20x1.5-6g", program=g76(20.2), insert="full", program_name="post.nc")
    op = nocut["operations"][0]
    assert "reason" in op and isinstance(op["suggested_final_x"], float)
    # Mid 6g d2 is 18.928; a full-profile insert cuts d2 = X + 0.866 (d2 − d3 basic): X ≈ 18.06.
    assert op["suggested_final_x"] == pytest.approx(18.062, abs=0.01)
    # The post-processor guide's pattern, on both.
    for x in (x_mid, 20.2):
        out = checked_g76("M20x1.5-6g", x, g76)
        assert "G76 X" in out


def test_a_path_given_as_program_is_named_as_a_path(tmp_path):
    p = tmp_path / "part.nc"
    p.write_text(G76_M20)
    with pytest.raises(ValueError, match=r"program '.*part\.nc' is a file's path: pass the program's text"):
        threadcheck.verify("M20x1.5-6g", program=str(p))


def test_messages_are_one_line():
    with pytest.raises(ValueError) as e:
        threadcheck.verify("M20x1.5-6g", program="G76.1 X1\n", program_name="two\nlines.nc")
    assert "\n" not in str(e.value) and str(e.value).startswith("two lines.nc:1:")
    with pytest.raises(ValueError, match="final_x is not a finite number"):
        threadcheck.verify("M10x1.5-6g", final_x=float("nan"))
    with pytest.raises(ValueError, match="verify takes no argument 'wire'"):
        threadcheck.render("verify", "json", thread="M10x1.5-6g", wire=1.0)


def test_svg_html_and_fix_outputs_are_the_cli_files(tmp_path):
    binary = os.environ.get("THREADCHECK_BIN")
    assert binary, "no threadcheck binary: build it (cargo build --release), put it on the PATH, or name it in THREADCHECK_BIN"
    prog = tmp_path / "m20.nc"
    prog.write_text(G76_M20)
    cli = {k: tmp_path / f"cli.{k}" for k in ("svg", "html", "fix")}
    r = subprocess.run([binary, "verify", "--thread", "M20x1.5-6g", "--program", str(prog), "--dialect", "fanuc",
                        "--insert", "full", "--svg", str(cli["svg"]), "--html", str(cli["html"]),
                        "--fix", str(cli["fix"])], capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    py = {k: tmp_path / f"py.{k}" for k in ("svg", "html", "fix")}
    report = threadcheck.verify("M20x1.5-6g", program=G76_M20, program_name=str(prog), dialect="fanuc",
                                insert="full", svg=py["svg"], html=str(py["html"]), fix=py["fix"])
    assert report["verdict"] == "fail"
    for k in ("svg", "html", "fix"):
        assert py[k].read_text() == as_keys(cli[k].read_text()), k
    # The corrected program moves X18.2 to the mid-tolerance X and changes nothing else.
    assert "G76 X18.058 Z-20.0 P900 Q300 F1.5" in py["fix"].read_text()
    # As strings.
    assert threadcheck.render("verify", "svg", thread="M20x1.5-6g", program=G76_M20, program_name=str(prog),
                              dialect="fanuc", insert="full") == as_keys(cli["svg"].read_text())
    text = threadcheck.render("limits", "text", designation="M10x1.5-6g")
    assert "8.862" in text and "8.994" in text
    # A failed run writes none of its files: the capability SVG first, then a bad HTML path.
    keep = tmp_path / "keep.svg"
    keep.write_text("old")
    with pytest.raises(ValueError):
        threadcheck.capability("M10x1.5-6g", samples=50, svg=keep, html=tmp_path / "no" / "such" / "dir.html")
    assert keep.read_text() == "old"


def test_every_function_documents_every_argument():
    import inspect

    for name in ("verify", "limits", "passes", "correct", "capability", "fit", "compare", "mill", "tap", "thread_mill", "render"):
        f = getattr(threadcheck, name)
        doc = inspect.getdoc(f)
        assert doc and len(doc) > 60, name
        hints = f.__annotations__
        assert "return" in hints, name
    # help() shows each argument with its type.
    sig = str(inspect.signature(threadcheck.verify))
    for arg in ("thread: 'Optional[Threads]'", "program: 'Optional[str]'", "svg: 'Optional[PathLike]'"):
        assert arg in sig, sig


def test_the_post_example_runs_and_corrects_x():
    import runpy

    here = os.path.dirname(os.path.abspath(__file__))
    example = os.path.join(here, "..", "examples", "post_g76.py")
    module = runpy.run_path(example)
    program, log = module["checked_program"]("M20x1.5-6g", 18.2)
    # X18.2 cuts d2 72 µm over 6g (the G76 sheet); the corrected X passes.
    assert log[0] == "X18.200: fail"
    assert log[1].startswith("X18.0") and log[1].endswith("pass (suggested by threadcheck)")
    assert "G76 X18.0" in program


def test_the_stubs_type_check_the_examples_strictly():
    # mypy is installed beside pytest (.ci/run); without it this test fails, it does not skip.
    from mypy import api as mypy

    here = os.path.dirname(os.path.abspath(__file__))
    out, err, status = mypy.run(["--strict", os.path.join(here, "..", "examples")])
    assert status == 0, out + err


def test_the_package_type_checks_strictly():
    # Regression: `thread_mill` returned a ThreadMillReport the module never imported.
    from mypy import api as mypy

    here = os.path.dirname(os.path.abspath(__file__))
    out, err, status = mypy.run(["--strict", os.path.join(here, "..", "threadcheck")])
    assert status == 0, out + err


def test_gcode_system_b_reads_g78_as_the_threading_cycle():
    # System B: G78 is system A's G92 box cycle, one pass per X word.
    prog = "G21 G97 S500 M3\nG0 X22.0 Z5.0\nG78 X19.2 Z-20.0 F1.5\nX18.8\nX18.2\n"
    p = threadcheck.passes(program=prog, dialect="fanuc", gcode_system="b")
    assert [q["x_end"] for q in p["passes"]] == [19.2, 18.8, 18.2]
    assert p["operations"][0]["cycle"] == "G78"
    with pytest.raises(ValueError, match="G78 is not a code of Fanuc G-code system A"):
        threadcheck.passes(program=prog, dialect="fanuc")


TAP_PROGRAM = """G21 G99 G18
T0505
G97 S1200 M3
G0 X0 Z5.0
G83 Z-25.0 R2.0 Q5000 F0.12
G80
T0606
G97 S300 M3
G0 X0 Z8.0
G84 Z-18.0 R5.0 F1.5
G80
M30
"""


def test_tap_checks_the_drill_against_d1():
    # ISO 965-2, M10x1.5-6H: D1 8.376-8.676. A drill of 8.5 passes, 8.0 fails by 376 µm.
    ok = threadcheck.tap(TAP_PROGRAM, '[tools]\n5 = "drill:8.5"\n6 = "tap:M10x1.5-6H"\n')
    assert ok["pass"]
    bad = threadcheck.tap(TAP_PROGRAM, '[tools]\n5 = "drill:8.0"\n6 = "tap:M10x1.5-6H"\n')
    d1 = next(c for c in bad["holes"][0]["checks"] if c["feature"] == "drill_diameter")
    assert not bad["pass"] and d1["deviation"] == pytest.approx(-376.0)
    # The drill that passes: ISO 2306's 8.5 for M10x1.5, the middle of D1 8.526.
    better = bad["holes"][0]["drill_that_passes"]
    assert (better["name"], better["source"]) == ("8.5", "iso2306-coarse")
    assert better["middle"] == pytest.approx(8.526)


def test_thread_mill_major_diameter_and_lead():
    # Ø6 single-form cutter on a helix of radius 7: the major diameter is 2(7 + 3) = 20.
    prog = "G17 G21 G90 G40\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X7 Y0 F100\n" + "".join(
        f"G3 X7 Y0 Z{-16 + 1.5 * k:.4f} I-7 J0 F150\n" for k in range(1, 11)) + "G0 Z50\nM30\n"
    r = threadcheck.thread_mill(prog, "M20x1.5-6H", 6.0)
    assert r["measured"]["major_diameter"] == pytest.approx(20.0, abs=1e-4)
    lead = next(c for c in r["checks"] if c["feature"] == "lead")
    assert lead["ok"]


def test_thread_mill_multi_form_rows_one_pitch_apart():
    # 8 rows 1.5 apart on one turn cut what one tooth cuts on eight turns (tests/threadmill.rs).
    mill = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "programs" / "threadmill"
    multi = threadcheck.thread_mill((mill / "m20-dc14-rows8.nc").read_text(), "M20x1.5-6H", 14.0,
                                    cutter_rows=8, cutter_row_pitch=1.5)
    single = threadcheck.thread_mill((mill / "m20-dc14.nc").read_text(), "M20x1.5-6H", 14.0)
    assert multi["measured"]["pitch_diameter"] == pytest.approx(single["measured"]["pitch_diameter"], abs=1e-4)
    with pytest.raises(ValueError, match="needs row_pitch"):
        threadcheck.thread_mill((mill / "m20-dc14-rows8.nc").read_text(), "M20x1.5-6H", 14.0, cutter_rows=8)


def test_thread_mill_taper_thread_is_gauged():
    # A 1/2-14 NPT fitting milled on its cone (tests/threadmill.rs derives the program): the
    # helices taper 1/16 on the diameter; a Ø10 cutter's groove stands the gauge 0.18 turn in.
    mill = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "programs" / "threadmill"
    r = threadcheck.thread_mill((mill / "npt-half-internal.nc").read_text(), cutter_diameter=10.0)
    assert r["kind"] == "internal" and r["verdict"] == "pass"
    checks = {c["feature"]: c for c in r["checks"]}
    assert checks["taper"]["value"] == pytest.approx(1 / 16, abs=2e-5)
    assert abs(checks["gauge_plane"]["value"]) < 1.0
    assert r["tooth_profile"]["pitch_diameter"] == pytest.approx(19.318551, abs=1e-3)


def test_tap_render_svg_and_html():
    # The tapping picture through the same door: the tap's bottom Z-18, the drill's Z-25.
    tools = '[tools]\n5 = "drill:8.5"\n6 = "tap:M10x1.5-6H"\n'
    svg = threadcheck.render("tap", "svg", program=TAP_PROGRAM, tools=tools)
    assert svg.startswith("<svg") and "tap Z-18" in svg and "drill Z-25" in svg
    html = threadcheck.render("tap", "html", program=TAP_PROGRAM, tools=tools)
    assert "<td>drill diameter</td>" in html


def test_mill_reads_the_dialect_of_the_program_name():
    # Regression: the API's mill took Fanuc whatever the name; a .ngc is LinuxCNC's (its
    # o-word loop). The boss of 36 chords of R23 gouges by the chord sag 23(1 - cos 5°).
    prog = ("G21 G90 G17\nG0 X23 Y0 Z2\nG1 Z-1 F100\n#1=10\no100 while [#1 LE 360]\n"
            "G1 X[23*COS[#1]] Y[23*SIN[#1]]\n#1=[#1+10]\no100 endwhile\nG0 Z2\nM2\n")
    target = 'x = "20*cos(t)"\ny = "20*sin(t)"\nt = [0, 360]\nmaterial = "inside"\n'
    r = threadcheck.mill(prog, target, 6.0, program_name="boss.ngc")
    assert r["gouge_max"] == pytest.approx(23 * (1 - math.cos(math.radians(5))), abs=1e-7)


def test_a_two_line_heidenhain_program_with_a_tiny_infeed_is_a_value_error():
    # Issue 42: I = 1e-12 mm asked V1 for 0.92 / 1e-12 = 9.2e11 cuts and aborted the
    # interpreter (an allocation of 7.36 TB); the cuts are counted first now.
    with pytest.raises(ValueError, match=r"9\.2e11 cuts, more than the 1000 passes"):
        threadcheck.verify("M20x1.5-6g", program="G0 X22 Z5\nG31 X20 Z-20 F1.5 U-0.92 I0.000000000001 V1\n",
                           program_name="tiny.nc", dialect="heidenhain")


def test_outputs_never_replace_inputs_and_follow_the_cli_writer(tmp_path):
    # Issue 42: Python writes through the command line's writer.
    insert = tmp_path / "i.toml"
    insert.write_text((pathlib.Path(__file__).parents[2] / "tests" / "data" / "insert-clearance-1deg.toml").read_text())
    before = insert.read_text()
    with pytest.raises(ValueError, match="is an input of this run; an output must not replace it"):
        threadcheck.verify("M10x1.5-6g", insert=str(insert), svg=str(insert))
    assert insert.read_text() == before
    # Two outputs on one file: refused, nothing written.
    both = tmp_path / "o.svg"
    with pytest.raises(ValueError, match="two outputs of this run name this file"):
        threadcheck.verify("M10x1.5-6g", insert="full", svg=both, html=both)
    assert not both.exists()
    # A kept mode, a followed link, a FIFO written in place.
    out = tmp_path / "kept.svg"
    out.write_text("old")
    os.chmod(out, 0o640)
    threadcheck.verify("M10x1.5-6g", insert="full", svg=out)
    assert out.read_text().startswith("<svg") or "<svg" in out.read_text()[:200]
    assert os.stat(out).st_mode & 0o777 == 0o640
    link = tmp_path / "link.svg"
    os.symlink(out, link)
    threadcheck.verify("M10x1.5-6g", insert="full", svg=link)
    assert link.is_symlink()
    fifo = tmp_path / "pipe.svg"
    os.mkfifo(fifo)
    got = []
    import threading

    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()))
    reader.start()
    threadcheck.verify("M10x1.5-6g", insert="full", svg=fifo)
    reader.join(10)
    assert stat_is_fifo(fifo) and got and b"<svg" in got[0][:400]
    # Issue 58: a FIFO no program reads is given up after 5 s (it was waited for forever).
    lonely = tmp_path / "lonely.svg"
    os.mkfifo(lonely)
    with pytest.raises(ValueError, match=r"lonely\.svg: a FIFO that no program read within 5 s"):
        threadcheck.verify("M10x1.5-6g", insert="full", svg=lonely)


def stat_is_fifo(path):
    import stat

    return stat.S_ISFIFO(os.stat(path).st_mode)


def test_every_function_takes_exactly_its_commands_keys():
    """Each function's keyword arguments are the keys its command's argument struct reads (the
    struct clap reads the command line's flags into), besides the paths it writes documents to."""
    import inspect
    from threadcheck import _threadcheck

    functions = {
        "verify": threadcheck.verify,
        "passes": threadcheck.passes,
        "limits": threadcheck.limits,
        "compare": threadcheck.compare,
        "fit": threadcheck.fit,
        "correct": threadcheck.correct,
        "capability": threadcheck.capability,
        "mill": threadcheck.mill,
        "tap": threadcheck.tap,
        "thread-mill": threadcheck.thread_mill,
    }
    documents = {"svg", "html", "fix", "markdown"}
    for command, function in functions.items():
        params = set(inspect.signature(function).parameters) - documents
        keys = set(_threadcheck.keys(command))
        assert params == keys, (command, sorted(keys - params), sorted(params - keys))


def test_verify_names_the_thread_from_the_program_text():
    # The comment above the G76 names M24x2 in capitals; the passes cut a bar, so 6G is 6g.
    text = "G0 X26 Z5\n(THREAD M24X2 6G)\nG76 P010060 Q100 R0.05\nG76 X21.546 Z-30 P1227 Q350 F2.0\nM30\n"
    r = threadcheck.verify(program=text, program_name="shaft.nc", insert="full")
    op = r["operations"][0]
    assert op["thread"]["designation"] == "M24X2-6g"
    assert (op["designation_from"], op["designation_line"]) == ("comment", 2)


def test_verify_checks_the_taps_of_a_lathe_program_too():
    # A turned M20x1.5 and an M8 tapped on the centre line after a Ø6.8 drill, named by comments.
    text = ("(M20X1.5-6G)\nG99 G0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\n"
            "T0505 (DRILL 6.8)\nG97 S900 M3\nG0 X0 Z5\nG83 Z-25 R2 Q5000 F0.1\nG80\n"
            "T0606 (TAP M8X1.25)\nG0 X0 Z8\nG84 Z-16 R5 F1.25\nG80\nM30\n")
    r = threadcheck.verify(program=text, program_name="part.nc", insert="full")
    assert [o["made"] for o in r["operations"]] == ["turned", "tapped"]
    tapped = r["operations"][1]
    assert tapped["tap"]["designation"] == "M8X1.25-6H" and tapped["drill"]["diameter"] == 6.8


KLARTEXT_TAP = """0 BEGIN PGM TAP MM
1 BLK FORM 0.1 Z X+0 Y+0 Z-20
2 TOOL CALL 1 Z S2000 ; DRILL 8.5
3 CYCL DEF 200 DRILLING ~
  Q200=+2 ;SET-UP CLEARANCE ~
  Q201=-25 ;DEPTH ~
  Q206=+150 ;FEED RATE FOR PLNGNG ~
  Q203=+0 ;SURFACE COORDINATE ~
  Q204=+50 ;2ND SET-UP CLEARANCE
4 L X+30 Y+10 R0 FMAX M99
5 TOOL CALL 2 Z S400 ; TAP M10X1.5
6 CYCL DEF 207 RIGID TAPPING NEW ~
  Q200=+2 ;SET-UP CLEARANCE ~
  Q201=-16 ;DEPTH OF THREAD ~
  Q239=+1.5 ;THREAD PITCH ~
  Q203=+0 ;SURFACE COORDINATE ~
  Q204=+50 ;2ND SET-UP CLEARANCE
7 L X+30 Y+10 R0 FMAX M99
8 L Z+100 R0 FMAX M30
9 END PGM TAP MM
"""


def test_klartext_tapping_from_python():
    """Issue 45: a Klartext program read from Python: cycle 207 taps M10x1.5 at (30, 10) to
    Z-16 over the Ø8.5 drill of cycle 200 (ISO 2306's tap drill, inside D1 8.376-8.676)."""
    r = threadcheck.tap(program=KLARTEXT_TAP, dialect="klartext")
    assert r["machine"]["machine_type"] == "mill"
    (h,) = r["holes"]
    assert (h["cycle"]["x"], h["cycle"]["y"], h["cycle"]["bottom"]) == (30.0, 10.0, -16.0)
    assert h["cycle"]["feed_word"] == "Q239"
    assert h["drill"]["diameter"] == 8.5
    assert h["pass"] is True


def test_a_tap_for_cycles_that_name_no_tool():
    """Issue 45 item 4: a G84 before any T takes the tap given (``tap``): M10x1.5 at S400 needs
    F = 400 x 1.5 = 600 per minute."""
    program = "G17 G21 G90 G94\nG0 X0 Y0 Z20 S400 M3\nG98 G84 X10 Y10 Z-15 R2 F600\nG80\nM30\n"
    with pytest.raises(ValueError):
        threadcheck.tap(program=program)
    r = threadcheck.tap(program=program, tap="M10x1.5-6H")
    (h,) = r["holes"]
    assert h["tap"]["designation"] == "M10x1.5-6H"
    assert [c["ok"] for c in h["checks"] if c["feature"] == "feed"] == [True]


def test_thread_mill_from_a_cam_tool_list():
    # A program as Autodesk's posts write it lists its tools, (T5  D=8. CR=0. - ... - thread mill):
    # the thread mill needs no tool table, and a shape option alone is refused, never dropped.
    mill = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "programs" / "threadmill"
    text = (mill / "m12-cam-helical-lead-in.nc").read_text()
    r = threadcheck.thread_mill(text)
    assert r["cutter"]["diameter"] == 8.0 and r["designation"] == "M12X1.75-6H"
    assert any(n.startswith("the thread mill T5 is the program's comment at line 4") for n in r["notes"])
    with pytest.raises(ValueError, match="cutter_angle describes the cutter cutter_diameter gives"):
        threadcheck.thread_mill(text, cutter_angle=55.0)


def test_tap_given_serves_a_tool_no_table_names():
    # T1 taps M10x1.5 (F600 at S400) and no table names it: ``tap`` gives it, stated.
    prog = "G17 G21 G90 G94\nT1 M6\nG0 X0 Y0 Z20 S400 M3\nG98 G84 X10 Y10 Z-15 R2 F600\nG80\nM30\n"
    with pytest.raises(ValueError, match="T1, which no tool table names"):
        threadcheck.tap(prog)
    r = threadcheck.tap(prog, tap="M10x1.5-6H")
    assert r["pass"] and r["holes"][0]["tap"]["designation_from"] == "given"


def test_tap_torque_follows_the_tap_makers_equation():
    # M10x1.5 after an Ø8.5 drill, a plug hand tap in C45 (Ck 45: kc 3900 N/mm², K 1.35):
    # tan 30° · 3900 · 1.35 · 1.5² · (10 + 17) / 24 000 = 7.694 N·m; at S400, 7.694 · 2π · 400 / 60 000 kW.
    program = ("G21 G17 G90 G94\nT5 M6\nG0 X0 Y0 S1200 M3\nG43 H5 Z5.\nG98 G81 Z-25. R2. F150.\nG80\n"
               "T6 M6\nG0 X0 Y0 S400 M3\nG43 H6 Z5.\nG98 G84 Z-18. R3. F600.\nG80\nM30\n")
    tools = '[tools]\n5 = "drill:8.5"\n6 = "tap:M10x1.5-6H"\n'
    r = threadcheck.tap(program, tools=tools, dialect="fanuc", material="C45", tap_kind="hand-plug")
    t = r["holes"][0]["torque"]
    assert t["newton_metres"] == pytest.approx(math.tan(math.radians(30)) * 3900 * 1.35 * 2.25 * 27 / 24000, rel=1e-12)
    assert t["power_kw"] == pytest.approx(t["newton_metres"] * 2 * math.pi * 400 / 60000, rel=1e-12)
    with pytest.raises(ValueError, match="unknown material"):
        threadcheck.tap(program, tools=tools, dialect="fanuc", material="unobtainium")
    # A spindle of 5 N·m holds less than 7.694 N·m: a warning, the verdict the thread's.
    r = threadcheck.tap(program, tools=tools, dialect="fanuc", material="C45", tap_kind="hand-plug",
                        machine='name = "small"\nspindle_torque_nm = 5\n')
    h = r["holes"][0]
    assert h["torque"]["exceeds_spindle"] and h["torque"]["spindle_torque_nm"] == 5
    assert any(n.startswith("warning: the tap needs 7.69 N·m, more than the spindle's 5 N·m") for n in h["notes"])
    assert r["pass"]


# Issue 65: a LinuxCNC lathe program (G7, the one-block G76 with I, J, K) that Fanuc's G76 refuses
# (no J); read as LinuxCNC it cuts M10x1.5 in tolerance with a full-profile insert (the Rust
# tests derive it).
_LINUXCNC = ("%\n(M10X1.5 THREAD)\nG7 G18 G21 G90\nS500 M3\nG0 X9.85 Z2\nG1 Z-25 F0.1\nG0 X12 Z2\n"
             "G76 P1.5 Z-20 I-2.15 J0.05 K1.84 Q29.5 R1.5 H1 E0 L0\nG0 X20 Z20\nM2\n%\n")


def test_a_modeline_and_a_project_file_choose_the_dialect(tmp_path):
    with pytest.raises(ValueError, match="word J is not part of the one-block G76"):
        threadcheck.verify(program=_LINUXCNC, program_name="part.nc", insert="full")
    modeline = _LINUXCNC.replace("%\n", "%\n(threadcheck: dialect=linuxcnc)\n", 1)
    r = threadcheck.verify(program=modeline, program_name="part.nc", insert="full")
    assert r["verdict"] == "pass" and r["dialect"] == "linuxcnc"
    assert "read with the program's modeline (line 2): dialect linuxcnc" in r["notes"]
    # The project file beside the file program_name names (Python may read the caller's files).
    (tmp_path / ".threadcheck.toml").write_text('dialect = "linuxcnc"\n')
    r = threadcheck.verify(program=_LINUXCNC, program_name=str(tmp_path / "part.nc"), insert="full")
    assert r["verdict"] == "pass"
    assert any(n.startswith("read with the project file ") and n.endswith(": dialect linuxcnc") for n in r["notes"])


def test_a_fusion_tool_library_is_a_tool_table():
    # Fusion's JSON: T5 a Ø8.5 drill, T6 a right-hand tap DC 10, TP 1.5 (M10x1.5, 6H by default).
    lib = json.dumps({"data": [
        {"type": "drill", "unit": "millimeters", "geometry": {"DC": 8.5}, "post-process": {"number": 5}},
        {"type": "tap right hand", "unit": "millimeters", "geometry": {"DC": 10, "TP": 1.5}, "post-process": {"number": 6}},
    ]})
    program = "G21 G17 G90 G95\nT5 M6\nG0 X0 Y0 S1200 M3\nG81 Z-25. R2. F0.1\nG80\nT6 M6\nS400 M3\nG84 Z-18. R3. F1.5\nG80\nM30\n"
    r = threadcheck.tap(program, tools=lib, dialect="fanuc")
    h = r["holes"][0]
    assert h["tap"]["designation"] == "M10x1.5-6H" and h["tap"]["designation_from"] == "tool"
    assert h["drill"]["diameter"] == 8.5 and r["pass"]


TAP_UNDER_G96 = """G21 G18 G90 G99
(M8X1.25 TAP)
T0606
G50 S2000
G96 S150 M3
G0 X0 Z5
G84 Z-10 R2 F1.25
G80
M30
"""


def test_the_controls_refusals_reach_python():
    # Issue 63: a tap under G96 turns at the clamp on the centre line: an error at its line
    # that fails the program.
    r = threadcheck.verify(program=TAP_UNDER_G96, dialect="fanuc")
    found = [(f["rule"], f["level"], f["line"]) for f in r["control"]]
    assert found == [("control.css_at_tap", "error", 7)]
    assert r["verdict"] == "fail"


def test_a_floating_holder_from_the_machine_file():
    # M8x1.25 at S600 wants F750; F727.5 is 3 % under it: a rigid holder fails it, a
    # floating one takes up to 5 % (750 x 0.95 = 712.5).
    program = "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F727.5\nG80\nM30\n"

    def feed(machine):
        r = threadcheck.tap(program, dialect="fanuc", machine=machine)
        return next(c for c in r["holes"][0]["checks"] if c["feature"] == "feed")

    assert feed('name = "vmc"\ntype = "mill"\n')["ok"] is False
    floating = feed('name = "vmc"\ntype = "mill"\ntap_holder = "floating"\n')
    assert (floating["ok"], floating["min"], floating["max"]) == (True, 712.5, 750.0)
