//! Issue 17: contour milling of the source documents' cams. Each value is derived by hand in its
//! comment; the programs are the seed programs as printed (tests/data/programs/milling) and our
//! own test programs beside them.

use crate::*;

fn mill_json(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let mut all = vec!["mill"];
    all.extend_from_slice(args);
    all.push("--json");
    let o = run_in(&data("."), &all);
    let v = serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o)));
    (o.status.code(), v)
}

/// A Ø40 boss cut with a Ø6 cutter along 36 chords of 10° of the centre circle R = 23 (a Fanuc
/// macro B WHILE loop): every chord end is exactly r = 3 from the boss, every chord's middle is
/// nearer by the chord sag R(1 − cos(Δθ/2)) = 23·(1 − cos 5°) = 0.0875219439 mm.
#[test]
fn boss_cut_by_chords_gouges_by_the_chord_sag() {
    let (code, v) = mill_json(&[
        "--program",
        "programs/milling/boss-chords.nc",
        "--tool-diameter",
        "6",
        "--target",
        "targets/boss.toml",
        "--tolerance",
        "0.01",
    ]);
    let sag = 23.0 * (1.0 - 5f64.to_radians().cos());
    let g = v["gouge_max"].as_f64().unwrap();
    assert!((g - sag).abs() < 1e-7, "gouge {g} against the sag {sag}");
    // At the middle of a chord: R·cos 5° from the centre.
    let at = &v["gouge_at"];
    let rho = at["x"].as_f64().unwrap().hypot(at["y"].as_f64().unwrap());
    assert!((rho - 23.0 * 5f64.to_radians().cos()).abs() < 1e-6, "{at}");
    assert_eq!(v["verdict"], "fail");
    assert_eq!(code, Some(1));
    // The same with a tolerance above the sag passes, and nothing is left over: every chord end
    // touches the boss.
    let (code, v) = mill_json(&[
        "--program",
        "programs/milling/boss-chords.nc",
        "--tool-diameter",
        "6",
        "--target",
        "targets/boss.toml",
        "--tolerance",
        "0.09",
    ]);
    assert_eq!((code, v["verdict"].as_str()), (Some(0), Some("pass")));
    assert!(v["leftover_max"].as_f64().unwrap() < 1e-9);
}

/// The cardioid cam program (seed 002) run in its N order: 64 levels Z−0.25 … Z−16, the cutter
/// offset radially by r = 3 instead of along the normal. The notes (§4.9.1) give the exact
/// distance from the tool centre to the curve at θ = 30°, 60°, 90°, 120°, 150°: 2.908, 2.642,
/// 2.227, 1.720, 1.252, so gouges of 0.092, 0.358, 0.773, 1.280, 1.748 mm. The centre at θ is
/// (a(1 + cos θ) + r)·(cos θ, sin θ).
#[test]
fn seed_cardioid_cam_gouges_0_773_at_90_degrees() {
    let (code, v) = mill_json(&[
        "--program",
        "programs/milling/seed002-cardioid-cam.nc",
        "--dialect",
        "dyna",
        "--n-order",
        "--tool-diameter",
        "6",
        "--target",
        "targets/cardioid.toml",
    ]);
    assert_eq!(code, Some(1));
    assert_eq!(v["levels"].as_array().unwrap().len(), 64);
    let profile = v["profile"].as_array().unwrap();
    for (theta, gouge) in [(30.0, 0.092), (60.0, 0.358), (90.0, 0.773), (120.0, 1.280), (150.0, 1.748)] {
        let t: f64 = f64::to_radians(theta);
        let rho = 20.0 * (1.0 + t.cos()) + 3.0;
        let (x, y) = (rho * t.cos(), rho * t.sin());
        let p = profile
            .iter()
            .find(|p| {
                (p["x"].as_f64().unwrap() - x).abs() < 1e-6 && (p["y"].as_f64().unwrap() - y).abs() < 1e-6
            })
            .unwrap_or_else(|| panic!("no tool centre at θ = {theta}°"));
        let got = -p["deviation"].as_f64().unwrap();
        assert!((got - gouge).abs() < 6e-4, "θ = {theta}°: gouge {got}, the notes {gouge}");
    }
    // As printed, N200 G28 / N205 M30 end the program after the first layer, and the reader says
    // the blocks are out of N order.
    let (_, printed) = mill_json(&[
        "--program",
        "programs/milling/seed002-cardioid-cam.nc",
        "--dialect",
        "dyna",
        "--tool-diameter",
        "6",
        "--target",
        "targets/cardioid.toml",
    ]);
    assert_eq!(printed["levels"].as_array().unwrap().len(), 1);
    assert!(printed["notes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n.as_str().unwrap().contains("not in N order")));
}

/// Our own program: the same cam with the cutter offset along the outward normal, θ = 0 … 120°
/// in 0.25° steps (away from the cusp, where the disk would reach the other lobe). Every chord
/// end is exactly r from the cam; the worst gouge is the sag of the longest chord of the centre
/// path, at θ = 0: the offset curve there is a circle of radius ρ + r = 4a/3 + 3 = 29.6667 mm
/// whose tangent turns 3/2 as fast as θ, so a 0.25° step spans 0.375° and the sag is
/// 29.6667·(1 − cos 0.1875°) = 0.15885 µm; radially offset, the same cam gouges 773 µm at 90°.
#[test]
fn cam_offset_along_the_normal_does_not_gouge_away_from_the_cusp() {
    let (_, v) = mill_json(&[
        "--program",
        "programs/milling/cam-normal-offset.nc",
        "--dialect",
        "dyna",
        "--tool-diameter",
        "6",
        "--target",
        "targets/cardioid.toml",
    ]);
    let sag = (4.0 * 20.0 / 3.0 + 3.0) * (1.0 - 0.1875f64.to_radians().cos());
    let g = v["gouge_max"].as_f64().unwrap();
    assert!((g - sag).abs() < 1e-9, "gouge {g} mm against the chord sag {sag} mm");
    assert!(v["gouge_at"]["t"].as_f64().unwrap() < 0.25);
}

/// The paraboloid dome (seed 004) as printed: it reads #14, never set, so every layer starts at
/// X = 0 + r = 6 and the Ø12 cutter plunges there, cutting a slot to the axis: at depth z the
/// cutter at (6, 0) reaches r + (a − 6) = a = √(90·(−z)/4) past the section's circle of radius a.
/// The deepest level cut is Z−39.95 (a = √(22.5·39.95) = 29.98124 mm); Z−40 is never machined.
#[test]
fn seed_paraboloid_names_hash_14_and_its_slot_gouges() {
    let (code, v) = mill_json(&[
        "--program",
        "programs/milling/seed004-paraboloid.nc",
        "--dialect",
        "dyna",
        "--tool-diameter",
        "12",
        "--target",
        "targets/paraboloid.toml",
    ]);
    assert_eq!(code, Some(1));
    let notes: Vec<&str> = v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert!(notes.iter().any(|n| n.to_string().contains("#14 is read before it is set")), "{notes:?}");
    assert!(
        notes.iter().any(|n| n.to_string().contains("Z-40") && n.to_string().contains("never machined")),
        "{notes:?}"
    );
    let g = v["gouge_max"].as_f64().unwrap();
    assert!((g - (22.5f64 * 39.95).sqrt()).abs() < 1e-6, "{g}");
    assert_eq!((v["gouge_at"]["x"].as_f64(), v["gouge_at"]["y"].as_f64()), (Some(6.0), Some(0.0)));
    assert_eq!(v["gouge_at"]["z"].as_f64(), Some(-39.95));
    // Level Z−10: a = 15, the slot's gouge.
    let l10 = v["levels"].as_array().unwrap().iter().find(|l| l["z"].as_f64() == Some(-10.0)).unwrap();
    assert!((l10["gouge"].as_f64().unwrap() - 15.0).abs() < 1e-6, "{l10}");
}

/// The picture: an SVG with the target, the swept area and the deviation, written atomically.
#[test]
fn mill_svg_shows_the_worst_level() {
    let dir = tempdir("mill-svg");
    let svg = dir.join("boss.svg");
    let o = run_in(
        &data("."),
        &[
            "mill",
            "--program",
            "programs/milling/boss-chords.nc",
            "--tool-diameter",
            "6",
            "--target",
            "targets/boss.toml",
            "--svg",
            svg.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("level Z-1") && text.contains("worst gouge 0.0875"));
}

/// The guide's picture is what the guide's command writes (deterministic bytes).
#[test]
fn committed_cam_picture_is_current() {
    let dir = tempdir("mill-readme");
    let svg = dir.join("cam.svg");
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let o = run_in(
        repo,
        &[
            "mill",
            "--program",
            "tests/data/programs/milling/seed002-cardioid-cam.nc",
            "--dialect",
            "dyna",
            "--n-order",
            "--tool-diameter",
            "6",
            "--target",
            "tests/data/targets/cardioid.toml",
            "--svg",
            svg.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let fresh = std::fs::read(&svg).unwrap();
    let committed = std::fs::read(repo.join("reports/mill-cardioid-cam.svg")).unwrap();
    assert!(
        fresh == committed,
        "reports/mill-cardioid-cam.svg is stale: rerun the mill command of docs/guide/tap-and-thread-mill.md"
    );
}

/// G3 arcs (I J and R): the centre circle R23.05 leaves 0.05 mm on the Ø40 boss all round (the
/// cutter's edge runs at 23.05 − 3 = 20.05); R23 is on size. Arcs are swept as chords within
/// 0.01 µm, so neither level gouges by more than that.
#[test]
fn boss_cut_by_arcs_leaves_the_offset() {
    let (_, v) = mill_json(&[
        "--program",
        "programs/milling/boss-arcs.nc",
        "--tool-diameter",
        "6",
        "--target",
        "targets/boss.toml",
    ]);
    let levels = v["levels"].as_array().unwrap();
    let at = |z: f64| levels.iter().find(|l| l["z"].as_f64() == Some(z)).unwrap();
    assert!((at(-1.0)["leftover"].as_f64().unwrap() - 0.05).abs() <= 1e-5, "{}", at(-1.0));
    assert!(at(-2.0)["leftover"].as_f64().unwrap() <= 1e-5, "{}", at(-2.0));
    for z in [-1.0, -2.0] {
        assert!(at(z)["gouge"].as_f64().unwrap() <= 1e-5, "{}", at(z));
    }
}

/// The toolpath is measured while it is read, each level once the cutter has moved on through
/// two other levels; a level the cutter comes back to is measured again with all its moves.
/// The Ø40 boss cut at Z−1, Z−2 and Z−3 by 3600 chords of R = 23 (each gouging by the sag
/// 23(1 − cos 0.05°) mm; more moves than the reader sends at once), then back at Z−1 one
/// straight move from (23, 0) to (0, 23): its middle lies 23/√2 from the centre, 3 + 20 − 23/√2
/// = 6.7365 mm into the boss. That gouge, at Z−1, is the worst.
#[test]
fn a_level_the_cutter_comes_back_to_is_measured_with_all_its_moves() {
    let chords = "#2=1\nWHILE [#2 LE 3600] DO1\nG1 X[23*COS[#2/10]] Y[23*SIN[#2/10]]\n#2=#2+1\nEND1\n";
    let text = format!(
        "G21 G90 G17\nG0 X23 Y0 Z2\nG1 Z-1 F100\n{chords}G1 Z-2\n{chords}G1 Z-3\n{chords}G1 Z-1\nG1 X0 Y23\nG0 Z2\nM30\n"
    );
    let dir = tempdir("mill-back");
    std::fs::write(dir.join("back.nc"), text).unwrap();
    let target = data("targets/boss.toml");
    let args = [
        "mill",
        "--program",
        "back.nc",
        "--tool-diameter",
        "6",
        "--target",
        target.to_str().unwrap(),
        "--json",
    ];
    let o = run_in(&dir, &args);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o)));
    let want = 3.0 + 20.0 - 23.0 / 2f64.sqrt();
    let g = v["gouge_max"].as_f64().unwrap();
    assert!((g - want).abs() < 1e-7, "gouge {g} against {want}");
    assert_eq!(v["gouge_at"]["z"], -1.0);
    let levels = v["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 3);
    let sag = 23.0 * (1.0 - 0.05f64.to_radians().cos());
    for l in &levels[1..] {
        assert!((l["gouge"].as_f64().unwrap() - sag).abs() < 1e-7, "{l}");
    }
}
