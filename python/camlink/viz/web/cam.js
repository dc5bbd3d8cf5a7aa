// The studio's cam design page: the motion program's segments edited in
// place; the server analyses the design in the core on each edit and
// answers with SVAJ over a turn, the profile and `camlink cam`'s report,
// which this page only presents. Every name and message is set as text.
//
// Data (see camlink.studio.cam.cam_payload): segments [{law, span_deg,
// lift, from_deg, ends}], laws, oscillating, error; for a valid design
// theta (rad), s, v, a, j (m or rad, per rad of cam angle), peaks
// {s: [value, θ°], …}, surface and pitch (cam frame, m, x y interleaved),
// base_radius (m), pressure (rad, not for a translating flat face) with
// pressure_limit (rad or null), curvature (1/m) with curvature_limit (1/m
// or null), and report (as `camlink cam --json`).
"use strict";
(function () {
  const F = camlinkFront;
  let D = null;     // the last reply's data
  let C = null;     // the last valid design's curves
  const svajBox = document.getElementById("svaj");
  const plots = [];
  const link = F.editor({
    reply: function (reply) {
      if (reply.type === "frames") show(reply.data);
      window.camlinkCam.answered = link.answered;
    },
  });

  // Presentation units: mm (translating) or degrees of swing (oscillating).
  function unit() {
    return D.oscillating ? { k: 180 / Math.PI, s: "°" } : { k: 1000, s: "mm" };
  }
  const NAMES = [["s", "s", ""], ["v", "s′", "/rad"], ["a", "s″", "/rad²"], ["j", "s‴", "/rad³"]];
  // The pressure angle's plot (degrees, whatever the follower) and the
  // surface's curvature κ = 1/ρ (1/mm; > 0 convex).
  const PRESSURE = ["p", "pressure angle φ", ""];
  const CURVATURE = ["k", "curvature κ = 1/ρ", ""];
  const LIMITS = { p: "pressure_limit", k: "curvature_limit" };

  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // -- the segments table -------------------------------------------------
  let rowsKey = "";
  const gestures = {};
  // An edit: "input" events send each value of a gesture (typing, the
  // spinner); "change" ends the gesture, sending the value only when no
  // input sent it and it differs from the data's (so a change at blur
  // makes no empty undo step).
  function edit(index, key, value, event) {
    const id = index + ":" + key, open = gestures[id];
    if (event === "change" && !open && D.segments[index][key] === value) return;
    if (!open) gestures[id] = "seg" + Date.now() + Math.random();
    if (event === "input" || !open) link.send({ op: "segment", index: index, key: key, value: value, gesture: gestures[id] });
    if (event === "change") { link.send({ op: "end", gesture: gestures[id] }); delete gestures[id]; }
  }
  function numberCell(index, key, value, step) {
    const td = el("td"), input = el("input");
    input.type = "number"; input.step = step; input.value = String(value);
    input.dataset.index = String(index); input.dataset.key = key;
    input.addEventListener("input", function () {
      const v = parseFloat(input.value);
      if (isFinite(v)) edit(index, key, v, "input");
    });
    input.addEventListener("change", function () {
      const v = parseFloat(input.value);
      if (isFinite(v)) edit(index, key, v, "change");
    });
    td.appendChild(input);
    return td;
  }
  function segments() {
    const body = document.querySelector("#segments tbody");
    document.getElementById("lift-head").textContent = D.oscillating ? "swing (°)" : "lift (m)";
    const key = D.segments.length + "|" + D.laws.join(",");
    if (key !== rowsKey) {
      rowsKey = key;
      body.textContent = "";
      D.segments.forEach(function (s, i) {
        const tr = el("tr");
        tr.appendChild(el("td", null, String(i)));
        const td = el("td"), pick = el("select");
        for (const law of D.laws) { const o = el("option", null, law); o.value = law; pick.appendChild(o); }
        pick.dataset.index = String(i); pick.dataset.key = "law";
        pick.addEventListener("change", function () { edit(i, "law", pick.value, "change"); });
        td.appendChild(pick); tr.appendChild(td);
        tr.appendChild(numberCell(i, "span_deg", s.span_deg, "any"));
        tr.appendChild(numberCell(i, "lift", s.lift, "any"));
        tr.appendChild(el("td", "cam-from"));
        body.appendChild(tr);
      });
    }
    const bad = {};
    if (D.report) for (const b of D.report.boundaries) if (b.continuity === 0) bad[b.after] = true;
    Array.from(body.rows).forEach(function (tr, i) {
      const s = D.segments[i];
      for (const input of tr.querySelectorAll("input, select")) {
        if (document.activeElement === input) continue;
        const v = input.dataset.key === "law" ? s.law : input.dataset.key === "span_deg" ? s.span_deg : s.lift;
        input.value = String(v);
      }
      tr.querySelector(".cam-from").textContent = s.from_deg === null ? "–" : s.from_deg.toFixed(2);
      tr.classList.toggle("cam-bad", !!bad[i]);
      tr.title = s.ends ? "polynomial end conditions: edit them in the file" : "";
    });
  }

  // -- SVAJ -----------------------------------------------------------------
  function scaleOf(key) { return key === "p" ? 180 / Math.PI : key === "k" ? 1e-3 : unit().k; }
  function unitOf(key, per) { return key === "p" ? "°" : key === "k" ? "1/mm" : unit().s + per; }
  function makePlots() {
    const u = unit();
    for (const [key, label, per] of NAMES.concat(D.pressure ? [PRESSURE] : [], D.curvature ? [CURVATURE] : [])) {
      const box = el("div", "cl-plot"), head = el("div", "cam-svaj-head");
      head.dataset.channel = key;
      box.appendChild(head); svajBox.appendChild(box);
      const p = { key: key, head: head, box: box, u: null, label: label + " (" + unitOf(key, per) + ")" };
      const opts = {
        width: 640, height: 150, legend: { show: false },
        cursor: { sync: { key: "svaj" }, drag: { x: false, y: false } },
        scales: { x: { time: false, range: [0, 360] } },
        axes: [{ label: "cam angle θ (°)", size: 34, labelSize: 14, incrs: [15, 30, 45, 90] },
               { label: key === "p" ? "φ (°)" : key === "k" ? "κ (1/mm)" : p.label, size: 64, labelSize: 14 }],
        series: [{}, { stroke: "#1f4e79", width: 1.4 }],
        hooks: {
          setCursor: [function (uu) { readout(p, uu.cursor.idx); }],
          draw: [function (uu) {
            if (!C || !C.report) return;
            const g = uu.ctx, dpr = window.devicePixelRatio || 1;
            g.save(); g.strokeStyle = "#999"; g.lineWidth = dpr; g.setLineDash([4 * dpr, 3 * dpr]);
            for (const b of C.report.boundaries) {
              const X = uu.valToPos(b.theta_deg, "x", true);
              g.strokeStyle = b.continuity === 0 ? "#c0392b" : "#999";
              g.beginPath(); g.moveTo(X, uu.bbox.top); g.lineTo(X, uu.bbox.top + uu.bbox.height); g.stroke();
            }
            g.restore();
            const limit = LIMITS[p.key] ? C[LIMITS[p.key]] : null;
            if (limit !== null && limit !== undefined) {
              // The limit, red dashed: ±φ_max, or κ = 1/ρ_min (convex).
              g.save(); g.strokeStyle = "#c0392b"; g.lineWidth = dpr; g.setLineDash([6 * dpr, 4 * dpr]);
              for (const sgn of p.key === "p" ? [1, -1] : [1]) {
                const Y = uu.valToPos(sgn * limit * scaleOf(p.key), "y", true);
                if (Y < uu.bbox.top || Y > uu.bbox.top + uu.bbox.height) continue;
                g.beginPath(); g.moveTo(uu.bbox.left, Y); g.lineTo(uu.bbox.left + uu.bbox.width, Y); g.stroke();
              }
              g.restore();
            }
          }],
        },
      };
      p.u = new uPlot(opts, [[0], [0]], box);
      plots.push(p);
    }
  }
  function readout(p, i) {
    const k = scaleOf(p.key), peak = C.peaks[p.key];
    let text = p.label + "   peak " + (peak[0] * k).toPrecision(6) + " at " + peak[1].toFixed(2) + "°";
    if (i !== null && i !== undefined && i >= 0 && i < C.theta.length) {
      text += "   cursor θ = " + (C.theta[i] * 180 / Math.PI).toFixed(2) + "°: " + (C[p.key][i] * k).toPrecision(6);
      cursor = i;
      profile();
    }
    p.head.textContent = text;
    p.head.dataset.peak = String(peak[0]);
  }
  function svaj() {
    if (!plots.length) makePlots();
    const deg = Array.from(C.theta, function (t) { return t * 180 / Math.PI; });
    for (const p of plots) {
      const k = scaleOf(p.key);
      p.u.setData([deg, Array.from(C[p.key], function (v) { return v * k; })]);
      readout(p, null);
    }
  }

  // -- the profile ------------------------------------------------------------
  let cursor = null;
  function inRanges(deg, ranges) {
    for (const r of ranges) if (deg >= r[0] && deg <= r[1]) return true;
    return false;
  }
  function profile() {
    const cv = document.getElementById("profile"), g = cv.getContext("2d");
    const W = cv.width, H = cv.height;
    g.clearRect(0, 0, W, H);
    if (!C) return;
    const R = C.report ? C.report.base_radius : C.base_radius;
    let big = R;
    for (let i = 0; i < C.surface.length; i++) big = Math.max(big, Math.abs(C.surface[i]));
    if (C.pitch) for (let i = 0; i < C.pitch.length; i++) if (isFinite(C.pitch[i])) big = Math.max(big, Math.abs(C.pitch[i]));
    const k = 0.45 * Math.min(W, H) / big, X = function (x) { return W / 2 + k * x; }, Y = function (y) { return H / 2 - k * y; };
    // grid at a round step (mm)
    const step = F.niceStep(2 * big * 1000, 8) / 1000;
    g.strokeStyle = "#eee"; g.lineWidth = 1;
    for (let v = -Math.ceil(big / step) * step; v <= big + 1e-12; v += step) {
      g.beginPath(); g.moveTo(X(v), 0); g.lineTo(X(v), H); g.stroke();
      g.beginPath(); g.moveTo(0, Y(v)); g.lineTo(W, Y(v)); g.stroke();
    }
    g.strokeStyle = "#aaa"; g.setLineDash([3, 3]);
    g.beginPath(); g.arc(X(0), Y(0), k * C.base_radius, 0, 2 * Math.PI); g.stroke();
    function curve(xy, colour, dash) {
      g.strokeStyle = colour; g.setLineDash(dash); g.beginPath();
      for (let i = 0; i < xy.length / 2; i++) {
        if (i === 0) g.moveTo(X(xy[0]), Y(xy[1])); else g.lineTo(X(xy[2 * i]), Y(xy[2 * i + 1]));
      }
      g.stroke();
    }
    if (C.pitch) curve(C.pitch, "#4e79a7", [5, 4]);
    g.lineWidth = 1.6; curve(C.surface, "#222", []); g.lineWidth = 1;
    // concave (under a flat face) and undercut ranges in red
    const bad = C.report.undercut_deg.concat(C.report.follower.endsWith("flat") ? C.report.concave_deg : []);
    g.fillStyle = "#d62728";
    for (let i = 0; i < C.theta.length; i++) {
      if (inRanges(C.theta[i] * 180 / Math.PI, bad)) g.fillRect(X(C.surface[2 * i]) - 1.5, Y(C.surface[2 * i + 1]) - 1.5, 3, 3);
    }
    g.fillStyle = "#222"; g.beginPath(); g.arc(X(0), Y(0), 3, 0, 2 * Math.PI); g.fill();
    if (cursor !== null && cursor < C.theta.length) {
      g.fillStyle = "#d62728"; g.beginPath(); g.arc(X(C.surface[2 * cursor]), Y(C.surface[2 * cursor + 1]), 4, 0, 2 * Math.PI); g.fill();
    }
    document.getElementById("profile-note").textContent =
      "profile in the cam frame, grid " + F.fmt(step * 1000, step * 1000) + " mm; base circle (dashed) R_b = " +
      F.fmt(C.base_radius * 1000, 1e-3) + " mm" + (C.pitch ? "; pitch curve dashed blue" : "") +
      (bad.length ? "; red: undercut or concave under a flat face" : "");
  }

  // -- the report -------------------------------------------------------------
  function num(v) { return String(Number(Number(v).toPrecision(6))); }
  function report() {
    const r = C.report, list = document.getElementById("checks");
    list.textContent = "";
    for (const c of r.checks) {
      const unitText = c.unit ? " " + c.unit : "";
      let text = c.name;
      if (c.value !== null && c.value !== undefined) text += ": " + num(c.value) + unitText;
      if (c.at_deg !== null && c.at_deg !== undefined) text += " at " + c.at_deg.toFixed(2) + "°";
      if (c.limit !== null && c.limit !== undefined) {
        text += " (limit " + num(c.limit) + unitText;
        if (c.margin !== null && c.margin !== undefined) text += ", margin " + num(c.margin);
        text += ")";
      }
      if (c.note) text += "; " + c.note;
      const li = el("li", c.ok ? "ok" : "fail", text);
      li.dataset.name = c.name;
      list.appendChild(li);
    }
    const lines = ["boundaries between segments:"];
    for (const b of r.boundaries) lines.push("  " + b.before + " → " + b.after + ": " + b.text);
    lines.push("factors   Cv       Ca       Cj");
    for (const f of r.factors) lines.push("  " + f.segment + " " + f.law + "  " + f.computed.map(function (v) { return v.toFixed(4); }).join("  "));
    lines.push(r.ok ? "all limits hold" : "some limits fail");
    document.getElementById("boundaries").textContent = lines.join("\n");
  }

  function show(data) {
    D = data;
    link.shown(data);
    segments();
    const stale = !!data.error;
    for (const id of ["svaj", "profile", "checks", "boundaries"]) document.getElementById(id).classList.toggle("stale", stale);
    if (data.error) {
      link.say(data.error + " (the curves shown are the last valid design's)", true);
      return;
    }
    if (data.seq !== undefined && data.seq > 1) link.say("");
    C = {
      theta: F.decode(data.theta), s: F.decode(data.s), v: F.decode(data.v), a: F.decode(data.a),
      j: F.decode(data.j), surface: F.decode(data.surface), pitch: data.pitch ? F.decode(data.pitch) : null,
      p: data.pressure ? F.decode(data.pressure) : null, pressure_limit: data.pressure_limit,
      k: data.curvature ? F.decode(data.curvature) : null, curvature_limit: data.curvature_limit,
      peaks: data.peaks, base_radius: data.base_radius, report: data.report,
    };
    if (cursor !== null && cursor >= C.theta.length) cursor = null;
    svaj();
    profile();
    report();
    if (document.getElementById("message").classList.contains("bad")) link.say("");
  }

  window.camlinkCam = { send: link.send, after: link.after, sent: link.sent, answered: 0,
                        data: function () { return D; }, curves: function () { return C; } };
})();
