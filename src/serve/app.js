// threadcheck's page: forms to the JSON API (/api/...), answers shown as tables and pictures.
// Text from a program or an answer is always set as text, never as markup.
"use strict";

const $ = (id) => document.getElementById(id);

/** POSTs `args` to /api/`path`; the answer's text, or an Error with the server's one line. */
async function api(path, args) {
  const r = await fetch("/api/" + path, {
    method: "POST",
    // The server names the page's fields in its messages (the API's keys for other clients).
    headers: { "Content-Type": "application/json", "X-Threadcheck-Reader": "page" },
    body: JSON.stringify(args),
  });
  const text = await r.text();
  if (!r.ok) {
    let message = text;
    try { message = JSON.parse(text).error; } catch (_) { /* not JSON: the text itself */ }
    throw new Error(message);
  }
  return text;
}

function show(id, on) { $(id).hidden = !on; }

/** The API's keys that an error may name, as the page's own controls. */
function fail(id, err) {
  // The server names the page's own fields in its messages (X-Threadcheck-Reader: page).
  $(id).textContent = err.message;
  show(id, true);
}

/** Before a new request: the last answer of `tab` is gone, so an error never stands above a
 *  verdict, a next step or a download that belonged to another thread. */
function clearResult(tab) {
  show(tab + "-error", false);
  show(tab === "limits" ? "limits-table" : tab + "-result", false);
  if (tab === "verify") {
    state.lastArgs = null;
    state.lastJson = null;
    $("verdict").textContent = "";
    $("next").textContent = "";
    $("next").hidden = true;
    $("operations").replaceChildren();
    $("download-fixed").hidden = true;
    $("picture").removeAttribute("src");
  }
}

/** A table from a header row and body rows; each cell is text, or [text, class]. */
function table(el, head, rows) {
  el.replaceChildren();
  const thead = el.createTHead().insertRow();
  for (const h of head) {
    const th = document.createElement("th");
    th.textContent = h;
    thead.appendChild(th);
  }
  const body = el.createTBody();
  for (const row of rows) {
    const tr = body.insertRow();
    for (const cell of row) {
      const td = tr.insertCell();
      if (Array.isArray(cell)) { td.textContent = cell[0]; td.className = cell[1]; } else { td.textContent = cell; }
    }
  }
  return el;
}

function fmt(x, digits) {
  return x === null || x === undefined ? "—" : Number(x).toFixed(digits);
}

function download(name, type, text) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

async function svgInto(img, path, args) {
  const svg = await api(path, args);
  if (img.dataset.url) URL.revokeObjectURL(img.dataset.url);
  img.dataset.url = URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
  img.src = img.dataset.url;
}

// ---- tabs
for (const tab of document.querySelectorAll("[role=tab]")) {
  tab.addEventListener("click", () => {
    for (const t of document.querySelectorAll("[role=tab]")) {
      const on = t === tab;
      t.setAttribute("aria-selected", String(on));
      $(t.getAttribute("aria-controls")).hidden = !on;
    }
  });
}

// ---- verify
const state = { programName: "", files: { insert: null, tools: null }, lastArgs: null, lastJson: null };

async function readFile(input) {
  const f = input.files && input.files[0];
  return f ? { name: f.name, text: await f.text() } : null;
}

$("program-file").addEventListener("change", async () => {
  const f = await readFile($("program-file"));
  if (f) {
    $("program").value = f.text;
    state.programName = f.name;
  }
});
$("program").addEventListener("input", () => { if (!$("program").value) state.programName = ""; });
$("insert").addEventListener("change", () => {
  $("tip-radius-label").hidden = $("insert").value !== "partial-r";
  $("insert-file-label").hidden = $("insert").value !== "file";
});
$("insert-file").addEventListener("change", async () => { state.files.insert = await readFile($("insert-file")); });
$("tools-file").addEventListener("change", async () => { state.files.tools = await readFile($("tools-file")); });

function verifyArgs() {
  const args = {};
  // An empty field: each thread as the program names it (a plan needs one).
  const threads = $("thread").value.split(",").map((s) => s.trim()).filter((s) => s);
  if (threads.length) args.thread = threads.length === 1 ? threads[0] : threads;
  if ($("internal").checked) args.internal = true;
  if ($("allow-nonstandard").checked) args.allow_nonstandard = true;
  if ($("gauge-only").checked) args.gauge_only = true;
  const program = $("program").value;
  if (program.trim()) {
    args.program = program;
    args.program_name = state.programName || "pasted program";
    if ($("dialect").value) args.dialect = $("dialect").value;
    if (state.files.tools) args.tools = state.files.tools.text;
  } else if ($("final-x").value !== "") {
    args.final_x = Number($("final-x").value);
  }
  switch ($("insert").value) {
    case "full": args.insert = "full"; break;
    case "partial-r": args.insert = "partial:" + $("tip-radius").value; break;
    case "file":
      if (!state.files.insert) throw new Error("choose the insert file (TOML)");
      args.insert_toml = state.files.insert.text;
      break;
    case "partial": args.insert = "partial"; break;
    default: break; // the program's tool, else the one assumed (a plan: the partial insert)
  }
  const coating = Number($("coating").value || 0);
  if (coating) {
    args.coating = coating;
    args.coating_limits = $("coating-limits").value;
  }
  return args;
}

function operationBlock(op, title, programLines) {
  const div = document.createElement("div");
  div.className = "operation";
  const h = document.createElement("h2");
  h.textContent = title;
  div.appendChild(h);
  const line = (cls, text) => {
    const p = document.createElement("p");
    p.className = cls;
    p.textContent = text;
    div.appendChild(p);
  };
  const pass = op.verdict === "pass";
  line("verdict-small " + (pass ? "ok" : "out"), pass ? "IN TOLERANCE" : "OUT OF TOLERANCE");
  if (op.reason) line("reason", (op.made === "milled" ? "Not checked: " : "Nothing is cut: ") + op.reason);
  if (op.correction) line("correction", "Next: " + op.correction.text);
  // A report in inch (its checks' cells say so): an X in inches, the mm beside it.
  const inch = (op.checks || []).some((c) => c.shown && c.shown.unit === "in");
  const x = (mm) => (inch ? fmt(mm / 25.4, 4) + " in (" + fmt(mm, 4) + " mm)" : fmt(mm, 4));
  if (!pass && op.suggested_final_x !== null && op.suggested_final_x !== undefined && !op.correction) {
    line("correction", "Next: a last pass at X" + x(op.suggested_final_x) + " puts d2 mid-tolerance");
  }
  // A correction resting on an insert nobody chose is withheld: the next step is the insert.
  const withheld = !op.correction && (op.notes || []).find((n) => String(n).startsWith("no correction is offered"));
  if (withheld) {
    line("correction", "Next: " + String(withheld));
  }
  for (const hint of op.hints || []) {
    line("hint", "Hint: " + (hint.text || hint.message || JSON.stringify(hint)));
  }
  if (op.checks) {
    // The cells every table shows (the JSON's `shown`): yes/no in words, signed deviations,
    // each in its unit; a failing size is OUT, a failing form check "form".
    const rows = op.checks.map((c) => {
      const s = c.shown || { value: fmt(c.value, 4), min: fmt(c.min, 4), max: fmt(c.max, 4), deviation: "", unit: "" };
      const unit = s.unit ? " " + s.unit : "";
      const failed = c.kind === "size" || !op.gauge_only ? "OUT" : "form";
      return [
        c.feature.replaceAll("_", " "),
        c.kind || "",
        s.value + (s.value && s.unit && s.unit !== "mm" ? unit : ""),
        s.min,
        s.max,
        s.deviation,
        c.unverified ? ["unverified", "form"] : c.ok ? ["ok", "ok"] : [failed, "out"],
        c.unverified ? (c.note ? c.note + "; " : "") + c.unverified : c.note || "",
      ];
    });
    const t = table(document.createElement("table"), ["check", "kind", "value", "min", "max", "deviation", "result", "note"], rows);
    t.className = "checks";
    div.appendChild(t);
  }
  if (op.passes && op.passes.length) {
    const rows = op.passes.map((p) => [
      String(p.index),
      String((p.start || 0) + 1),
      fmt(p.x, 4),
      fmt(p.z, 4),
      fmt(p.depth, 4),
      p.source_line ? String(p.source_line) : "—",
      p.source_line && programLines ? (programLines[p.source_line - 1] || "").trim() : "",
    ]);
    const t = table(document.createElement("table"), ["pass", "start", "X, mm", "Z, mm", "depth, mm", "line", "program"], rows);
    t.className = "passes";
    div.appendChild(t);
  }
  return div;
}

// A list of control findings: `✗ line 5 (G33.1): … — LinuxCNC refuses it: "…"`, an error
// marked ✗, a warning !, with what it assumed.
function controlList(findings) {
  const ul = document.createElement("ul");
  ul.className = "control";
  for (const f of findings) {
    const li = document.createElement("li");
    li.className = f.level;
    const alarm = f.alarm ? (f.alarm.number ? ` — ${f.alarm.control} alarm ${f.alarm.number}: "${f.alarm.text}"` : ` — ${f.alarm.control} refuses it: "${f.alarm.text}"`) : "";
    const assumed = f.assumed ? ` (assumed: ${f.assumed})` : "";
    li.textContent = `${f.level === "error" ? "✗" : "!"} Before the machine, line ${f.line} (${f.code}): ${f.message}${alarm}${assumed} [${f.rule}]`;
    ul.appendChild(li);
  }
  return ul;
}

$("verify-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("verify");
  $("verify-button").disabled = true;
  try {
    const args = verifyArgs();
    const json = await api("verify", args);
    const report = JSON.parse(json);
    state.lastArgs = args;
    state.lastJson = json;
    const pass = report.verdict === "pass";
    // Only form checks failing, with the insert's tip behind them: the newcomer's first run.
    const formOnly = !pass && (report.operations || [report]).every((o) => {
      const failing = (o.checks || []).filter((c) => !c.ok && !c.unverified && (c.kind === "size" || !o.gauge_only));
      return failing.length === 0 || (failing.every((c) => c.kind === "form") && (o.hints || []).some((h) => h.hint === "tip_radius"));
    });
    // Checks that rest on a tool nobody chose: said beside the verdict, never failed.
    const unverified = (report.operations || [report]).some((o) => (o.unverified || []).length);
    const form = unverified ? " — form unverified: tool not known (choose the insert or a tool table)" : "";
    // What the control refuses or a post got wrong (issue 63): errors fail the program.
    const control = report.control || [];
    const refused = control.filter((f) => f.level === "error").length;
    const opsPass = (report.operations || [report]).every((o) => o.verdict === "pass");
    const before = refused ? ` — ${refused} error${refused === 1 ? "" : "s"} before the machine (the control refuses it, or the tool breaks)` : "";
    $("verdict").textContent = pass
      ? (unverified ? "IN TOLERANCE" + form : "IN TOLERANCE: every check passes")
      : refused && opsPass
        ? "WILL NOT RUN AS WRITTEN" + before
        : formOnly
          ? "OUT OF TOLERANCE — form only: the insert's tip (a full-profile insert cuts the standard root; 'gauge only' judges the sizes)" + before
          : "OUT OF TOLERANCE" + form + before;
    $("verdict").className = "verdict " + (pass ? "ok" : "out");
    const nexts = (report.operations || [report])
      .filter((o) => o.correction)
      .map((o) => o.correction.text);
    $("next").textContent = "Next: " + nexts.join("; ");
    $("next").hidden = nexts.length === 0;
    const ops = $("operations");
    ops.replaceChildren();
    const lines = args.program ? args.program.split(/\r?\n/) : null;
    // Each control finding under the operation it concerns (the same process at the same line).
    const shown = new Set();
    const findingsOf = (made, line) => {
      // A milled thread is one operation: its findings are its own at any line.
      const mine = control.filter((f, i) => !shown.has(i) && f.made === made && (made === "milled" || f.line === line) && shown.add(i));
      return mine.length ? controlList(mine) : null;
    };
    if (report.operations) {
      for (const op of report.operations) {
        const line = op.made === "tapped" ? op.cycle.line : op.made === "milled" ? (op.helices ? op.helices[0].line : op.line) : op.operation.source_line;
        const list = findingsOf(op.made || "turned", line);
        // The operation's block with its findings at its end.
        const add = (block) => { if (list) block.appendChild(list); ops.appendChild(block); };
        // A tapped hole and a milled thread (issue 46) carry their own keys, not `operation`.
        if (op.made === "tapped") {
          const t = op.tap;
          const from = t.designation_from === "comment" ? ` (named by the comment at line ${t.designation_line})` : t.designation_from === "inferred" ? " (inferred from its lead and drill)" : "";
          // A machining centre's hole's place: the holes of one pattern cycle share its line.
          const at = op.cycle.x !== null && op.cycle.y !== null ? ` (X${+op.cycle.x.toFixed(3)} Y${+op.cycle.y.toFixed(3)})` : "";
          add(operationBlock(op, `Tapped: ${op.cycle.code} at line ${op.cycle.line}${at}, tap ${t.designation}${from}`, null));
          continue;
        }
        if (op.made === "milled") {
          add(operationBlock(op, op.designation ? `Milled: ${op.designation}, ${op.helices.length} helices from line ${op.helices[0].line}` : `Milled: helices from line ${op.line}`, null));
          continue;
        }
        const o = op.operation;
        // The thread it was checked against, and where it came from when the program named it.
        const from = { comment: `named by the comment at line ${op.designation_line}`, inferred: "inferred from the lead and diameter it cuts", tool: "from the tool table", given: "" }[op.designation_from] || "";
        const thread = `${op.thread.designation}${from ? ` (${from})` : ""}`;
        add(operationBlock(op, `Operation ${o.index}: ${o.cycle} at line ${o.source_line}, ${thread}`, lines));
      }
    } else {
      ops.appendChild(operationBlock(report, `${report.thread.designation}: a generated plan`, null));
    }
    const rest = control.filter((f, i) => !shown.has(i));
    if (rest.length) ops.appendChild(controlList(rest));
    const notes = report.notes || [];
    if (notes.length) {
      const ul = document.createElement("ul");
      ul.className = "notes";
      for (const n of notes) {
        const li = document.createElement("li");
        li.textContent = typeof n === "string" ? n : JSON.stringify(n);
        ul.appendChild(li);
      }
      ops.appendChild(ul);
    }
    const fixable = (report.operations || []).some((o) => o.correction && o.correction.editable);
    $("download-fixed").hidden = !fixable;
    show("verify-result", true);
    await svgInto($("picture"), "verify/svg", args);
    // How many answers the result shows (a test waits for the next one).
    $("verify-result").dataset.run = String(Number($("verify-result").dataset.run || 0) + 1);
  } catch (err) {
    fail("verify-error", err);
  } finally {
    $("verify-button").disabled = false;
  }
});

function fixedName() {
  const name = state.programName || "program.nc";
  const dot = name.lastIndexOf(".");
  return dot > 0 ? name.slice(0, dot) + "-fixed" + name.slice(dot) : name + "-fixed";
}

$("download-fixed").addEventListener("click", async () => {
  try { download(fixedName(), "text/plain", await api("verify/fix", state.lastArgs)); } catch (err) { fail("verify-error", err); }
});
$("download-html").addEventListener("click", async () => {
  try { download("threadcheck-report.html", "text/html", await api("verify/html", state.lastArgs)); } catch (err) { fail("verify-error", err); }
});
$("download-json").addEventListener("click", () => download("threadcheck-report.json", "application/json", state.lastJson));

// ---- compare
function compareArgs() {
  return { thread: $("compare-thread").value.trim(), insert: $("compare-insert").value };
}

$("compare-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("compare");
  try {
    const c = JSON.parse(await api("compare", compareArgs()));
    const rows = c.strategies.map((s) => [
      s.infeed,
      s.schedule,
      String(s.passes),
      fmt(s.chip_first, 3),
      fmt(s.chip_max, 3),
      fmt(100 * s.trailing_share, 0) + " %",
      fmt(s.pitch_diameter, 4),
      s.pass ? ["in tolerance", "ok"] : [(s.failed || []).join(", ").replaceAll("_", " "), "out"],
    ]);
    table($("compare-table"), ["infeed", "schedule", "passes", "first chip mm²", "largest chip mm²", "trailing edge", "d2", "result"], rows);
    const r = c.recommended;
    $("compare-recommended").textContent = r
      ? `Recommended: ${r.infeed}, ${r.schedule} (${r.grounds.join(", ").replaceAll("-", " ")})` +
        (r.any_in_tolerance === false ? "; none is in tolerance with this insert" : "")
      : "No strategy is recommended";
    $("compare-recommended").className = "verdict " + (r && r.any_in_tolerance !== false ? "ok" : "neutral");
    show("compare-result", true);
  } catch (err) {
    fail("compare-error", err);
  }
});
$("compare-download-html").addEventListener("click", async () => {
  try { download("threadcheck-compare.html", "text/html", await api("compare/html", compareArgs())); } catch (err) { fail("compare-error", err); }
});

// ---- fit
$("fit-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("fit");
  try {
    const args = { thread: $("fit-thread").value.trim() };
    if ($("fit-bolt-x").value !== "") args.bolt_final_x = Number($("fit-bolt-x").value);
    if ($("fit-nut-x").value !== "") args.nut_final_x = Number($("fit-nut-x").value);
    const f = JSON.parse(await api("fit", args));
    const fits = f.verdict === "fits";
    $("fit-verdict").textContent = (fits ? "FITS" : "INTERFERES") + `: clearance ${fmt(f.clearance_um, 1)} µm on the flanks`;
    $("fit-verdict").className = "verdict " + (fits ? "ok" : "out");
    show("fit-result", true);
    await svgInto($("fit-picture"), "fit/svg", args);
  } catch (err) {
    fail("fit-error", err);
  }
});

// ---- limits
$("limits-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("limits");
  try {
    const args = { thread: $("limits-thread").value.trim() };
    if ($("limits-rolled").checked) args.rolled = true;
    const l = JSON.parse(await api("limits", args));
    const rows = [];
    for (const side of ["external", "internal"]) {
      const s = l[side];
      if (!s) continue;
      for (const [k, v] of Object.entries(s)) {
        if (v && typeof v === "object" && "max" in v) {
          rows.push([side + " " + s.class, k.replaceAll("_", " "), fmt(v.min, 4), fmt(v.max, 4)]);
        }
      }
    }
    // A rolled external thread (issue 64): the dies' pitch diameter, their root and the blank
    // that fills the full crest, each one diameter (min and max alike).
    if (l.rolled) {
      const r = l.rolled;
      for (const [k, v] of [["pitch diameter the dies set", r.pitch_diameter], ["root the dies form", r.root_diameter],
        ["blank for the full crest", r.blank_for_full_crest]]) {
        rows.push(["rolled", k, fmt(v, 4), fmt(v, 4)]);
      }
    }
    table($("limits-table"), ["thread", "size", "min, mm", "max, mm"], rows);
    show("limits-table", true);
  } catch (err) {
    fail("limits-error", err);
  }
});

// ---- tap and thread mill: a program (pasted or a file) and their own fields
function programFrom(prefix) {
  const program = $(prefix + "-program").value;
  if (!program.trim()) throw new Error("paste the program, or choose its file");
  const args = { program, program_name: state[prefix + "Name"] || "pasted program" };
  if ($(prefix + "-dialect").value) args.dialect = $(prefix + "-dialect").value;
  return args;
}
for (const prefix of ["tap", "mill"]) {
  // One list of dialects: the Verify tab's (our own markup).
  $(prefix + "-dialect").innerHTML = $("dialect").innerHTML;
  $(prefix + "-program-file").addEventListener("change", async () => {
    const f = await readFile($(prefix + "-program-file"));
    if (f) {
      $(prefix + "-program").value = f.text;
      state[prefix + "Name"] = f.name;
    }
  });
}

function tapArgs() {
  const args = programFrom("tap");
  // An empty table: the tools the program names.
  if ($("tap-tools").value.trim()) args.tools = $("tap-tools").value;
  // The torque wants the workpiece; the tap's kind only with it.
  if ($("tap-material").value) {
    args.material = $("tap-material").value;
    if ($("tap-kind").value) args.tap_kind = $("tap-kind").value;
  }
  return args;
}
$("tap-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("tap");
  try {
    const args = tapArgs();
    const r = JSON.parse(await api("tap", args));
    $("tap-verdict").textContent = (r.pass ? "IN TOLERANCE" : "OUT OF TOLERANCE") + `: ${r.holes.length} tapping cycles, ${r.drills} drilling cycles`;
    $("tap-verdict").className = "verdict " + (r.pass ? "ok" : "out");
    const rows = [];
    for (const h of r.holes) {
      for (const c of h.checks) {
        // A failing drill: the drill that passes (its name and where it comes from).
        const pass = h.drill_that_passes;
        const better = c.feature === "drill_diameter" && !c.ok && pass && pass.name
          ? ` — a drill that passes: ${pass.source === "inch-gauge" ? pass.name : "Ø" + pass.name + " mm"} (${pass.source}; D1's middle ${pass.middle.toFixed(3)} mm)`
          : "";
        // In the program's units (an inch program's in inches, its feed in in/min), unit beside.
        const inch = h.cycle.units === "inch" && ["mm", "mm/min", "mm/rev"].includes(c.unit);
        const unit = inch ? c.unit.replace("mm", "in") : c.unit;
        const places = inch && c.unit === "mm/min" ? 1 : 4;
        const v = (x) => fmt(inch && x !== null && x !== undefined ? x / 25.4 : x, places);
        const withUnit = (x) => (x === null || x === undefined || !unit ? v(x) : v(x) + " " + unit);
        rows.push([`${h.cycle.code} line ${h.cycle.line}`, [h.tap.designation, "t"], [c.feature.replaceAll("_", " "), "t"],
          withUnit(c.value), v(c.min), v(c.max), c.ok ? ["ok", "ok"] : ["OUT", "out"], [c.note + better, "t"]]);
      }
      // Reported beside the checks, never failed (issue 64): how much thread the drill leaves,
      // the torque the tap needs and the spindle it is held against.
      const at = `${h.cycle.code} line ${h.cycle.line}`;
      if (h.thread_percent) {
        const p = h.thread_percent;
        rows.push([at, [h.tap.designation, "t"], ["thread %", "t"], fmt(p.percent, 1), fmt(p.band[0], 0), fmt(p.band[1], 0), "",
          ["% of thread the drill leaves (100 % = 0.6495·P a side); the shops' band, a named default", "t"]]);
      }
      if (h.torque) {
        const t = h.torque;
        const spindle = t.spindle_torque_nm !== undefined ? fmt(t.spindle_torque_nm, 2) : "—";
        rows.push([at, [h.tap.designation, "t"], ["torque N·m", "t"], fmt(t.newton_metres, 2), "—", spindle,
          t.exceeds_spindle ? ["OVER", "out"] : "",
          [(h.cycle.units === "inch" ? `${fmt(t.newton_metres * 8.850746, 1)} lbf·in; ` : "") +
            `the tap maker's equation: ${t.material}, kc ${t.kc} N/mm², ${t.tap_kind} tap, K ${t.k}` + (t.power_kw !== null ? `; ${fmt(t.power_kw, 3)} kW at the spindle` : ""), "t"]]);
      }
    }
    table($("tap-table"), ["cycle", "tap", "check", "value", "min", "max", "", "note"], rows);
    show("tap-result", true);
    await svgInto($("tap-picture"), "tap/svg", args);
  } catch (err) {
    fail("tap-error", err);
  }
});
$("tap-download-html").addEventListener("click", async () => {
  try { download("threadcheck-tap.html", "text/html", await api("tap/html", tapArgs())); } catch (err) { fail("tap-error", err); }
});

function millArgs() {
  const args = programFrom("mill");
  // Empty fields: the thread and the cutter the program names; the cutter's shape goes with a
  // diameter typed here.
  if ($("mill-thread").value.trim()) args.thread = $("mill-thread").value.trim();
  const num = (id, key) => { if ($(id).value !== "") args[key] = Number($(id).value); };
  num("mill-diameter", "cutter_diameter");
  if (args.cutter_diameter !== undefined) {
    num("mill-angle", "cutter_angle");
    num("mill-tip", "cutter_tip_radius");
    num("mill-rows", "cutter_rows");
    num("mill-row-pitch", "cutter_row_pitch");
  } else if (["mill-angle", "mill-tip", "mill-rows", "mill-row-pitch"].some((id) => $(id).value !== "")) {
    throw new Error("the tooth angle, tip radius, rows and row pitch describe a cutter Ø typed here: give it too");
  }
  num("mill-comp", "comp_radius");
  num("mill-blank", "blank_diameter");
  return args;
}
$("mill-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  clearResult("mill");
  try {
    const args = millArgs();
    const r = JSON.parse(await api("thread-mill", args));
    const ok = r.verdict === "pass";
    $("mill-verdict").textContent = ok ? "IN TOLERANCE" : "OUT OF TOLERANCE";
    $("mill-verdict").className = "verdict " + (ok ? "ok" : "out");
    $("mill-distortion").textContent =
      `As milled: pitch diameter ${fmt(r.measured.pitch_diameter, 4)} mm; the tooth profile alone ${fmt(r.tooth_profile.pitch_diameter, 4)} mm: ` +
      `profile distortion ${fmt(r.distortion_pitch_diameter_um, 1)} µm, flanks ${fmt(r.distortion_flank_angles_deg[0], 3)}° / ${fmt(r.distortion_flank_angles_deg[1], 3)}°`;
    table($("mill-table"), ["check", "value", "min", "max", "deviation µm", ""],
      r.checks.map((c) => [c.feature.replaceAll("_", " "), fmt(c.value, 4), fmt(c.min, 4), fmt(c.max, 4),
        c.ok ? "" : fmt(c.deviation_um, 1), c.ok ? ["ok", "ok"] : ["OUT", "out"]]));
    show("mill-result", true);
    await svgInto($("mill-picture"), "thread-mill/svg", args);
  } catch (err) {
    fail("mill-error", err);
  }
});
$("mill-download-html").addEventListener("click", async () => {
  try { download("threadcheck-thread-mill.html", "text/html", await api("thread-mill/html", millArgs())); } catch (err) { fail("mill-error", err); }
});
