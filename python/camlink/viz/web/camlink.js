// camlink's front end: the mechanism on a canvas with axes, grid and tick
// numbers, traces, springs, force arrows, zoom and pan, time controls and
// keyboard, and linked uPlot plots with a readout at the cursor. Shared by
// the studio page (served as a file) and `camlink view`'s self-contained
// HTML (inlined). Every name from a model is set as text (textContent),
// never parsed as markup.
//
// Data (`setData`): t (s), ok (1 where the mechanism assembled), bodies
// (0 is the ground), poses (per moving body x, y, φ interleaved; m, rad),
// scene (shapes in body frames, m), traces, springs, forces, channels
// (names, units, values), plots (channel names), handles (studio), info,
// marks (dead-centre and toggle positions: t, kind, label, x, y).
//
// A click on a pin or a handle picks its point: its velocity and
// acceleration, from its body's channels (v_P = v + ω × A s′,
// a_P = a + α × A s′ − ω² A s′), are drawn as arrows and read out.
// An array is a list of numbers, or {f64: base64} / {f32: base64}
// little-endian (a bare base64 string is float64), or a typed array (the
// studio's binary replies, `unpack`).
"use strict";
(function (root) {
  function decode(a) {
    if (a === null || a === undefined) return new Float64Array(0);
    if (ArrayBuffer.isView(a)) return a;
    if (typeof a === "string") a = { f64: a };
    if (Array.isArray(a)) return Float64Array.from(a, function (v) { return v === null ? NaN : v; });
    const b64 = a.f64 !== undefined ? a.f64 : a.f32;
    const bin = atob(b64), n = bin.length, bytes = new Uint8Array(n);
    for (let i = 0; i < n; i++) bytes[i] = bin.charCodeAt(i);
    return a.f64 !== undefined ? new Float64Array(bytes.buffer) : new Float32Array(bytes.buffer);
  }

  // A binary reply of the studio (camlink.studio.pack): a uint32 n, n
  // bytes of JSON, then float64s; each {buf: [k, m]} in the JSON is the
  // m values from the k-th float64 (a view, not a copy). The references
  // are replaced after parsing, by a walk over objects and arrays only (a
  // reviver would be called for every number of the reply).
  const utf8 = new TextDecoder();
  function unpack(buf) {
    const n = new DataView(buf).getUint32(0, true), base = 4 + n;
    function walk(v) {
      if (Array.isArray(v)) {
        for (let i = 0; i < v.length; i++) { const x = v[i]; if (x !== null && typeof x === "object") v[i] = walk(x); }
        return v;
      }
      const ref = v.buf;
      if (Array.isArray(ref)) return new Float64Array(buf, base + 8 * ref[0], ref[1]);
      for (const k in v) { const x = v[k]; if (x !== null && typeof x === "object") v[k] = walk(x); }
      return v;
    }
    return walk(JSON.parse(utf8.decode(new Uint8Array(buf, 4, n))));
  }

  // Sets e's text only when it differs: an unchanged text leaves the page's
  // layout as it was (an edit redraws without laying the page out again).
  function setText(e, text) { if (e.textContent !== text) e.textContent = text; }

  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // A step of 1, 2 or 5 × 10^k giving about `n` intervals over `span`.
  function niceStep(span, n) {
    const raw = span / n, p = Math.pow(10, Math.floor(Math.log10(raw))), f = raw / p;
    return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
  }
  function fmt(v, step) {
    const d = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    const s = v.toFixed(Math.min(d, 10));
    return s === "-0" || /^-0\.0*$/.test(s) ? s.slice(1) : s;
  }

  const COLORS = ["#4e79a7", "#f28e2b", "#59a14f", "#b07aa1", "#76b7b2", "#edc948", "#ff9da7", "#9c755f", "#e15759", "#bab0ac"];
  const EDGE = "#333";

  function create(host, opts) {
    opts = opts || {};
    const W = opts.width || 720, H = opts.height || 520;
    const dpr = window.devicePixelRatio || 1;
    host.classList.add("camlink");
    const left = el("div", "cl-left"), right = el("div", "cl-right");
    host.appendChild(left); host.appendChild(right);
    const bar = el("div", "cl-bar");
    const lengthSel = el("select"); lengthSel.id = "units-length";
    for (const u of ["mm", "m"]) { const o = el("option", null, u); o.value = u; lengthSel.appendChild(o); }
    const angleSel = el("select"); angleSel.id = "units-angle";
    for (const u of ["deg", "rad"]) { const o = el("option", null, u); o.value = u; angleSel.appendChild(o); }
    const fitBtn = el("button", null, "fit"); fitBtn.type = "button"; fitBtn.id = "fit";
    bar.appendChild(el("span", null, "lengths ")); bar.appendChild(lengthSel);
    bar.appendChild(el("span", null, " angles ")); bar.appendChild(angleSel);
    bar.appendChild(fitBtn);
    left.appendChild(bar);
    const stage = el("canvas"); stage.id = "stage"; stage.tabIndex = 0;
    stage.width = W * dpr; stage.height = H * dpr;
    stage.style.width = W + "px"; stage.style.height = H + "px";
    left.appendChild(stage);
    const ctx = stage.getContext("2d", { alpha: false });
    const controls = el("div", "cl-controls"); controls.id = "controls";
    const play = el("button", null, "play"); play.type = "button"; play.id = "play";
    const slider = el("input"); slider.type = "range"; slider.id = "slider"; slider.min = "0"; slider.step = "1"; slider.value = "0";
    const speedSel = el("select"); speedSel.id = "speed";
    for (const s of ["0.1", "0.25", "0.5", "1", "2", "4"]) { const o = el("option", null, s + "×"); o.value = s; if (s === "1") o.selected = true; speedSel.appendChild(o); }
    const timeLabel = el("span", "cl-time"); timeLabel.id = "time";
    controls.appendChild(play); controls.appendChild(slider);
    const sl = el("label", null, "speed "); sl.appendChild(speedSel); controls.appendChild(sl);
    controls.appendChild(timeLabel);
    left.appendChild(controls);
    const band = el("canvas", "cl-band"); band.id = "reach";
    band.width = 380 * dpr; band.height = 6 * dpr; band.style.width = "380px"; band.style.height = "6px";
    left.appendChild(band);
    const status = el("div", "cl-status"); status.id = "status";
    left.appendChild(status);
    const readout = el("div", "cl-readout"); readout.id = "readout";
    left.appendChild(readout);
    const pickBox = el("div", "cl-pick-readout"); pickBox.id = "picked";
    left.appendChild(pickBox);
    const info = el("div", "cl-info"); info.id = "info";
    left.appendChild(info);
    const plotsBox = el("div", "cl-plots"); plotsBox.id = "plots";
    right.appendChild(plotsBox);
    const addPlot = el("button", null, "add plot"); addPlot.type = "button"; addPlot.id = "add-plot";
    right.appendChild(addPlot);

    let D = null;           // decoded data
    let frame = 0, playing = false, speed = 1, last = null, simTime = 0;
    let lengthUnit = "mm", angleUnit = "deg";
    // View: world box fitted to the stage, then zoom and pan.
    let scale = 1, ox = 0, oy = 0;   // screen X = ox + x·scale, Y = oy − y·scale
    let fitted = false;
    let hover = null, drag = null, panning = null;
    let picked = null;      // {label, body, s}: the point whose v and a are drawn
    const stats = { frames: 0, renderMs: 0, lastDraw: 0 };
    const plots = [];
    const api = { onEdit: null, onEditEnd: null };

    function fit() {
      if (!D) return;
      const [x0, x1, y0, y1] = D.box;
      scale = Math.min(W / (x1 - x0), H / (y1 - y0));
      ox = (W - (x1 - x0) * scale) / 2 - x0 * scale;
      oy = (H - (y1 - y0) * scale) / 2 + y1 * scale;
    }
    function toScreen(x, y) { return [ox + x * scale, oy - y * scale]; }
    function toWorld(X, Y) { return [(X - ox) / scale, (oy - Y) / scale]; }

    function pose(b, k) {
      if (b === 0) return [0, 0, 0];
      const a = D.poses[b - 1];
      return [a[3 * k], a[3 * k + 1], a[3 * k + 2]];
    }
    function place(q, s) {
      const c = Math.cos(q[2]), sn = Math.sin(q[2]);
      return [q[0] + c * s[0] - sn * s[1], q[1] + sn * s[0] + c * s[1]];
    }
    // The row drawn: the frame if solved, else the nearest solved row
    // (-1 when none is).
    function shownRow(k) {
      if (!D.ok || D.ok[k]) return k;
      for (let d = 1; d < D.rows; d++) {
        if (k - d >= 0 && D.ok[k - d]) return k - d;
        if (k + d < D.rows && D.ok[k + d]) return k + d;
      }
      return -1;
    }

    function setData(data) {
      const first = D === null;
      const n = decode(data.t).length;
      const d = {
        title: data.title, t: decode(data.t), rows: n,
        ok: data.ok ? Uint8Array.from(data.ok) : null,
        bodies: data.bodies, poses: (data.poses || []).map(decode),
        scene: data.scene, traces: data.traces || [], springs: data.springs || [],
        forces: data.forces || [], handles: data.handles || [], info: data.info || [],
        box: data.box, cams: data.cams || [], marks: data.marks || [],
        channels: { names: data.channels.names, units: data.channels.units,
                    values: data.channels.values.map(function (v) { return v === null ? null : decode(v); }) },
        plots: data.plots || [],
      };
      d.index = {};
      d.channels.names.forEach(function (nm, i) { d.index[nm] = i; });
      d.bodyIndex = {};
      d.bodies.forEach(function (nm, i) { d.bodyIndex[nm] = i; });
      D = d;
      if (!fitted) { fit(); fitted = true; }
      slider.max = String(n - 1);
      if (frame >= n) frame = n - 1;
      simTime = D.t[frame];
      drawBand();
      const infoKey = JSON.stringify([D.info, D.marks, angleUnit]);
      if (infoKey !== shownInfo) { shownInfo = infoKey; showInfo(); }
      const bad = D.ok ? D.ok.reduce(function (s, v) { return s + (v ? 0 : 1); }, 0) : 0;
      setText(status, bad ? ("does not assemble at " + bad + " of " + n + " times (marked red)") : "");
      status.classList.toggle("cl-bad", bad > 0);
      if (first) {
        for (const c of D.plots) newPlot(c);
      } else {
        for (const p of plots) p.refresh();
      }
      render();
    }
    // The lines under the stage: the mechanism's, then its marks. The
    // lines shown are kept and their text set; only a change in their
    // number adds or removes lines.
    let shownInfo = null;
    function showInfo() {
      const lines = info.children, want = D.info.length + D.marks.length;
      while (lines.length > want) info.removeChild(info.lastChild);
      while (lines.length < want) info.appendChild(el("div"));
      D.info.forEach(function (text, i) {
        const line = lines[i];
        if (line.className !== "") line.className = "";
        delete line.dataset.t; delete line.dataset.crank;
        setText(line, text);
      });
      D.marks.forEach(function (m, i) {
        const line = lines[D.info.length + i], a = ((m.crank % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI);
        if (line.className !== "cl-mark") line.className = "cl-mark";
        setText(line, m.label + " at t = " + m.t.toFixed(5) + " s, crank " + angleText(a));
        line.dataset.t = String(m.t); line.dataset.crank = String(m.crank);
      });
    }

    // The unreachable times, red on a strip under the slider.
    let shownBand = null;
    function drawBand() {
      const key = (D.ok ? D.ok.join("") : "") + "|" + D.marks.map(function (m) { return m.t; }).join(",") + "|" + D.rows;
      if (key === shownBand) return;
      shownBand = key;
      const g = band.getContext("2d");
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.fillStyle = "#cfe3cf"; g.fillRect(0, 0, 380, 6);
      const t0 = D.t[0], span = (D.t[D.rows - 1] - t0) || 1;
      g.fillStyle = "#222";
      for (const m of D.marks) g.fillRect((m.t - t0) / span * 380 - 1, 0, 2, 6);
      if (!D.ok) return;
      g.fillStyle = "#d62728";
      for (let i = 0; i < D.rows; i++) {
        if (!D.ok[i]) g.fillRect(i / Math.max(1, D.rows - 1) * 380 - 1, 0, 380 / Math.max(1, D.rows - 1) + 2, 6);
      }
    }

    // -- stage ----------------------------------------------------------
    function grid() {
      const [wx0, wy1] = toWorld(0, 0), [wx1, wy0] = toWorld(W, H);
      const k = lengthUnit === "mm" ? 1000 : 1;
      const step = niceStep(Math.max(wx1 - wx0, wy1 - wy0) * k, 10) / k;
      ctx.lineWidth = 1;
      ctx.strokeStyle = "#ececec";
      ctx.beginPath();
      for (let x = Math.ceil(wx0 / step) * step; x <= wx1; x += step) { const X = Math.round(toScreen(x, 0)[0]) + 0.5; ctx.moveTo(X, 0); ctx.lineTo(X, H); }
      for (let y = Math.ceil(wy0 / step) * step; y <= wy1; y += step) { const Y = Math.round(toScreen(0, y)[1]) + 0.5; ctx.moveTo(0, Y); ctx.lineTo(W, Y); }
      ctx.stroke();
      // Axes through the origin, when in view.
      ctx.strokeStyle = "#b0b0b0"; ctx.beginPath();
      const [X0, Y0] = toScreen(0, 0);
      if (X0 >= 0 && X0 <= W) { ctx.moveTo(X0, 0); ctx.lineTo(X0, H); }
      if (Y0 >= 0 && Y0 <= H) { ctx.moveTo(0, Y0); ctx.lineTo(W, Y0); }
      ctx.stroke();
      // Tick numbers along the bottom and the left edge.
      ctx.fillStyle = "#666"; ctx.font = "10px system-ui, sans-serif";
      ctx.textAlign = "center"; ctx.textBaseline = "bottom";
      for (let x = Math.ceil(wx0 / step) * step; x <= wx1; x += step) {
        ctx.fillText(fmt(x * k, step * k), toScreen(x, 0)[0], H - 2);
      }
      ctx.textAlign = "left"; ctx.textBaseline = "middle";
      for (let y = Math.ceil(wy0 / step) * step; y <= wy1; y += step) {
        const Y = toScreen(0, y)[1];
        if (Y < H - 14) ctx.fillText(fmt(y * k, step * k), 3, Y);
      }
      ctx.textAlign = "right"; ctx.textBaseline = "top";
      ctx.fillText("x, y in " + lengthUnit, W - 4, 4);
    }

    function bodyColor(b) { return COLORS[(b - 1) % COLORS.length]; }

    function polyPath(pts, q, closed) {
      const p = new Path2D();
      for (let i = 0; i < pts.length; i += 2) {
        const g = place(q, [pts[i], pts[i + 1]]), s = toScreen(g[0], g[1]);
        if (i === 0) p.moveTo(s[0], s[1]); else p.lineTo(s[0], s[1]);
      }
      if (closed) p.closePath();
      return p;
    }

    function drawScene(k) {
      const S = D.scene, B = D.bodyIndex;
      const q = D.bodies.map(function (_, b) { return pose(b, k); });
      ctx.lineJoin = "round"; ctx.lineCap = "round";
      for (const c of S.curves) {
        const b = B[c.body], path = polyPath(c.points, q[b], c.closed);
        if (c.role === "cam") { ctx.fillStyle = b ? bodyColor(b) + "55" : "#ddd"; ctx.fill(path); }
        ctx.strokeStyle = EDGE; ctx.lineWidth = 1.3;
        ctx.setLineDash(c.role === "slot" ? [6, 3] : []);
        ctx.stroke(path);
        ctx.setLineDash([]);
      }
      for (const o of S.outlines) {
        const b = B[o.body], path = polyPath(o.points, q[b], true);
        ctx.fillStyle = bodyColor(b) + "99"; ctx.fill(path);
        ctx.strokeStyle = EDGE; ctx.lineWidth = 1.2; ctx.stroke(path);
      }
      for (const l of S.links) {
        const b = B[l.body], path = polyPath(l.points, q[b], l.points.length > 4);
        ctx.strokeStyle = EDGE; ctx.lineWidth = 14; ctx.stroke(path);
        ctx.strokeStyle = bodyColor(b); ctx.lineWidth = 11.5; ctx.stroke(path);
        if (l.points.length > 4) { ctx.fillStyle = bodyColor(b); ctx.fill(path); }
      }
      for (const g of S.gears) {
        const c = toScreen.apply(null, place(q[B[g.body]], g.centre));
        ctx.strokeStyle = EDGE; ctx.lineWidth = 1; ctx.setLineDash([8, 3, 2, 3]);
        ctx.beginPath(); ctx.arc(c[0], c[1], g.radius * scale, 0, 2 * Math.PI); ctx.stroke();
        ctx.setLineDash([]);
      }
      for (const f of S.faces) {
        const qb = q[B[f.body]], a = place(qb, [f.s[0] - f.half * f.u[0], f.s[1] - f.half * f.u[1]]), e = place(qb, [f.s[0] + f.half * f.u[0], f.s[1] + f.half * f.u[1]]);
        const A = toScreen(a[0], a[1]), E = toScreen(e[0], e[1]);
        ctx.strokeStyle = EDGE; ctx.lineWidth = 2.5; ctx.beginPath(); ctx.moveTo(A[0], A[1]); ctx.lineTo(E[0], E[1]); ctx.stroke();
      }
      for (const g of S.guides) {
        const qi = q[B[g.body_i]], qj = q[B[g.body_j]];
        const a = place(qi, [g.s_i[0] - g.half * g.v_i[0], g.s_i[1] - g.half * g.v_i[1]]), e = place(qi, [g.s_i[0] + g.half * g.v_i[0], g.s_i[1] + g.half * g.v_i[1]]);
        const A = toScreen(a[0], a[1]), E = toScreen(e[0], e[1]);
        ctx.strokeStyle = "#777"; ctx.lineWidth = 1.5; ctx.setLineDash([10, 4]);
        ctx.beginPath(); ctx.moveTo(A[0], A[1]); ctx.lineTo(E[0], E[1]); ctx.stroke(); ctx.setLineDash([]);
        const c = toScreen.apply(null, place(qj, g.s_j)), ang = -(qi[2] + Math.atan2(g.v_i[1], g.v_i[0]));
        ctx.save(); ctx.translate(c[0], c[1]); ctx.rotate(ang);
        const bj = B[g.body_j];
        ctx.fillStyle = bj ? bodyColor(bj) : "#ddd"; ctx.strokeStyle = EDGE; ctx.lineWidth = 1.2;
        ctx.fillRect(-16, -9, 32, 18); ctx.strokeRect(-16, -9, 32, 18); ctx.restore();
      }
      for (const r of S.rods) {
        const a = toScreen.apply(null, place(q[B[r.body_i]], r.s_i)), e = toScreen.apply(null, place(q[B[r.body_j]], r.s_j));
        ctx.strokeStyle = EDGE; ctx.lineWidth = 3; ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(e[0], e[1]); ctx.stroke();
      }
      for (const s of D.springs) drawSpring(s, q);
    }

    // Pins on top of the links and the traces.
    function drawPins(k) {
      const S = D.scene, B = D.bodyIndex;
      const q = D.bodies.map(function (_, b) { return pose(b, k); });
      for (const p of S.pins) {
        const c = toScreen.apply(null, place(q[B[p.body_i]], p.s_i));
        if (p.grounded) {
          ctx.fillStyle = "#999"; ctx.strokeStyle = EDGE; ctx.lineWidth = 1;
          ctx.beginPath(); ctx.moveTo(c[0], c[1]); ctx.lineTo(c[0] - 10, c[1] + 16); ctx.lineTo(c[0] + 10, c[1] + 16); ctx.closePath();
          ctx.fill(); ctx.stroke();
          ctx.beginPath(); ctx.moveTo(c[0] - 14, c[1] + 16); ctx.lineTo(c[0] + 14, c[1] + 16); ctx.stroke();
        }
        ctx.fillStyle = "#fff"; ctx.strokeStyle = EDGE; ctx.lineWidth = 1.4;
        ctx.beginPath(); ctx.arc(c[0], c[1], 6, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
        ctx.fillStyle = EDGE; ctx.beginPath(); ctx.arc(c[0], c[1], 1.4, 0, 2 * Math.PI); ctx.fill();
      }
    }

    function drawSpring(s, q) {
      const a = toScreen.apply(null, place(q[D.bodyIndex[s.body_i]], s.s_i));
      const e = toScreen.apply(null, place(q[D.bodyIndex[s.body_j]], s.s_j));
      if (s.kind === "torsion") {
        // A spiral of two and a half turns round the pin, 8 to 16 px.
        ctx.strokeStyle = "#2a7f62"; ctx.lineWidth = 1.3; ctx.beginPath();
        for (let i = 0; i <= 120; i++) {
          const f = i / 120, ang = f * 5 * Math.PI, r = 8 + 8 * f;
          const X = a[0] + r * Math.cos(ang), Y = a[1] - r * Math.sin(ang);
          if (i === 0) ctx.moveTo(X, Y); else ctx.lineTo(X, Y);
        }
        ctx.stroke();
        return;
      }
      const dx = e[0] - a[0], dy = e[1] - a[1], L = Math.hypot(dx, dy) || 1;
      const ux = dx / L, uy = dy / L, nx = -uy, ny = ux;
      ctx.strokeStyle = "#2a7f62"; ctx.lineWidth = 1.4; ctx.beginPath(); ctx.moveTo(a[0], a[1]);
      if (s.kind === "damper") {
        const m = 0.45 * L;
        ctx.lineTo(a[0] + ux * m, a[1] + uy * m);
        ctx.moveTo(a[0] + ux * m + nx * 7, a[1] + uy * m + ny * 7); ctx.lineTo(a[0] + ux * m - nx * 7, a[1] + uy * m - ny * 7);
        ctx.moveTo(a[0] + ux * (m - 6) + nx * 10, a[1] + uy * (m - 6) + ny * 10); ctx.lineTo(a[0] + ux * (m + 10) + nx * 10, a[1] + uy * (m + 10) + ny * 10);
        ctx.moveTo(a[0] + ux * (m - 6) - nx * 10, a[1] + uy * (m - 6) - ny * 10); ctx.lineTo(a[0] + ux * (m + 10) - nx * 10, a[1] + uy * (m + 10) - ny * 10);
        ctx.moveTo(a[0] + ux * (m + 10) + nx * 10, a[1] + uy * (m + 10) + ny * 10); ctx.lineTo(a[0] + ux * (m + 10) - nx * 10, a[1] + uy * (m + 10) - ny * 10);
        ctx.moveTo(a[0] + ux * (m + 4), a[1] + uy * (m + 4));
      } else {
        const turns = 8, lead = 0.15 * L;
        ctx.lineTo(a[0] + ux * lead, a[1] + uy * lead);
        for (let i = 0; i < 2 * turns; i++) {
          const f = lead + (i + 0.5) / (2 * turns) * (L - 2 * lead), side = i % 2 ? -7 : 7;
          ctx.lineTo(a[0] + ux * f + nx * side, a[1] + uy * f + ny * side);
        }
        ctx.lineTo(e[0] - ux * lead, e[1] - uy * lead);
      }
      ctx.lineTo(e[0], e[1]); ctx.stroke();
    }

    function channel(name) { const i = D.index[name]; return i === undefined ? null : D.channels.values[i]; }

    function drawTraces(k) {
      D.traces.forEach(function (tr, n) {
        const xs = channel(tr.x), ys = channel(tr.y);
        if (!xs || !ys) return;
        ctx.strokeStyle = ["#c0392b", "#8e44ad", "#16a085", "#d35400"][n % 4]; ctx.lineWidth = 1.5;
        ctx.beginPath();
        let pen = false;
        for (let i = 0; i < D.rows; i++) {
          if (!(xs[i] === xs[i]) || !(ys[i] === ys[i])) { pen = false; continue; }
          const s = toScreen(xs[i], ys[i]);
          if (pen) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]);
          pen = true;
        }
        ctx.stroke();
        if (xs[k] === xs[k]) {
          const s = toScreen(xs[k], ys[k]);
          ctx.fillStyle = ctx.strokeStyle; ctx.beginPath(); ctx.arc(s[0], s[1], 3.5, 0, 2 * Math.PI); ctx.fill();
          ctx.font = "11px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "bottom";
          ctx.fillText(tr.name, s[0] + 6, s[1] - 4);
        }
      });
    }

    function drawForces(k) {
      if (!D.forces.length) return;
      let biggest = 0;
      const vs = D.forces.map(function (f) {
        const fx = channel(f.fx), fy = channel(f.fy);
        let m = 0;
        for (let i = 0; i < D.rows; i++) if (fx[i] === fx[i]) m = Math.max(m, Math.hypot(fx[i], fy[i]));
        biggest = Math.max(biggest, m);
        return [fx, fy];
      });
      const len = 0.18 * Math.min(W, H) / (biggest || 1);
      D.forces.forEach(function (f, n) {
        const fx = vs[n][0][k], fy = vs[n][1][k];
        if (!(fx === fx)) return;
        const a = toScreen.apply(null, place(pose(D.bodyIndex[f.body], k), f.s));
        const e = [a[0] + fx * len, a[1] - fy * len], ang = Math.atan2(e[1] - a[1], e[0] - a[0]);
        ctx.strokeStyle = ctx.fillStyle = "#d62728"; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(e[0], e[1]); ctx.stroke();
        ctx.beginPath(); ctx.moveTo(e[0], e[1]);
        ctx.lineTo(e[0] - 9 * Math.cos(ang - 0.4), e[1] - 9 * Math.sin(ang - 0.4));
        ctx.lineTo(e[0] - 9 * Math.cos(ang + 0.4), e[1] - 9 * Math.sin(ang + 0.4)); ctx.closePath(); ctx.fill();
        ctx.font = "10px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "top";
        ctx.fillText(f.joint + " " + Math.hypot(fx, fy).toPrecision(3) + " N", e[0] + 4, e[1] + 2);
      });
    }

    // Dead-centre and toggle positions: a diamond where the pin is then.
    function drawMarks() {
      ctx.font = "10px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "middle";
      for (const m of D.marks) {
        const s = toScreen(m.x, m.y);
        ctx.fillStyle = m.kind === "toggle" ? "#8c564b" : "#222"; ctx.beginPath();
        ctx.moveTo(s[0], s[1] - 6); ctx.lineTo(s[0] + 6, s[1]); ctx.lineTo(s[0], s[1] + 6); ctx.lineTo(s[0] - 6, s[1]);
        ctx.closePath(); ctx.fill();
        ctx.fillText(m.label, s[0] + 9, s[1]);
      }
    }

    // The picked point's velocity and acceleration at row k (m/s, m/s²),
    // from its body's channels; null when they are not there (yet).
    function pointMotion(pk, k) {
      const b = pk.body, v = ["vx", "vy", "omega", "ax", "ay", "alpha"].map(function (c) { return channel(b + "." + c); });
      if (D.bodyIndex[b] === 0) return { v: [0, 0], a: [0, 0] };
      if (v.some(function (x) { return !x; })) return null;
      const q = pose(D.bodyIndex[b], k), c = Math.cos(q[2]), sn = Math.sin(q[2]);
      const rx = c * pk.s[0] - sn * pk.s[1], ry = sn * pk.s[0] + c * pk.s[1];
      const w = v[2][k], al = v[5][k];
      return { v: [v[0][k] - w * ry, v[1][k] + w * rx],
               a: [v[3][k] - al * ry - w * w * rx, v[4][k] + al * rx - w * w * ry] };
    }
    // Arrow lengths (px per m/s and per m/s²): the point's largest speed
    // and acceleration over the cycle drawn 0.15 of the stage's smaller side.
    function vectorScales(pk) {
      let vm = 0, am = 0;
      for (let i = 0; i < D.rows; i++) {
        if (D.ok && !D.ok[i]) continue;
        const m = pointMotion(pk, i);
        if (!m) return null;
        vm = Math.max(vm, Math.hypot(m.v[0], m.v[1])); am = Math.max(am, Math.hypot(m.a[0], m.a[1]));
      }
      const L = 0.15 * Math.min(W, H);
      return [vm > 0 ? L / vm : 0, am > 0 ? L / am : 0];
    }
    function arrow(a, e, color, label) {
      const ang = Math.atan2(e[1] - a[1], e[0] - a[0]);
      ctx.strokeStyle = ctx.fillStyle = color; ctx.lineWidth = 2.5;
      ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(e[0], e[1]); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(e[0], e[1]);
      ctx.lineTo(e[0] - 10 * Math.cos(ang - 0.4), e[1] - 10 * Math.sin(ang - 0.4));
      ctx.lineTo(e[0] - 10 * Math.cos(ang + 0.4), e[1] - 10 * Math.sin(ang + 0.4)); ctx.closePath(); ctx.fill();
      ctx.font = "bold 11px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "bottom";
      ctx.fillText(label, e[0] + 5, e[1] - 3);
    }
    function drawPicked(k) {
      if (!picked) { setText(pickBox, ""); return; }
      const m = pointMotion(picked, k), sc = m ? vectorScales(picked) : null;
      const g = place(pose(D.bodyIndex[picked.body], k), picked.s), P = toScreen(g[0], g[1]);
      ctx.strokeStyle = "#000"; ctx.lineWidth = 2; ctx.beginPath(); ctx.arc(P[0], P[1], 9, 0, 2 * Math.PI); ctx.stroke();
      if (!m || !sc) { setText(pickBox, picked.label + ": velocity and acceleration on their way"); return; }
      arrow(P, [P[0] + m.v[0] * sc[0], P[1] - m.v[1] * sc[0]], "#1f77b4", "v");
      arrow(P, [P[0] + m.a[0] * sc[1], P[1] - m.a[1] * sc[1]], "#9467bd", "a");
      const k2 = lengthUnit === "mm" ? 1000 : 1, u = lengthUnit;
      const f = function (x) { return (x * k2).toPrecision(6); };
      setText(pickBox, picked.label + " (" + picked.body + "): v = (" + f(m.v[0]) + ", " + f(m.v[1]) + ") " + u + "/s, |v| = " +
        f(Math.hypot(m.v[0], m.v[1])) + " " + u + "/s\n" + " ".repeat(picked.label.length + picked.body.length + 3) +
        "a = (" + f(m.a[0]) + ", " + f(m.a[1]) + ") " + u + "/s², |a| = " + f(Math.hypot(m.a[0], m.a[1])) + " " + u + "/s²");
      pickBox.dataset.vx = String(m.v[0]); pickBox.dataset.vy = String(m.v[1]);
      pickBox.dataset.ax = String(m.a[0]); pickBox.dataset.ay = String(m.a[1]);
      pickBox.dataset.row = String(k);
    }
    // What a click can pick: the handles, and each pin on its moving body.
    function pickables() {
      const out = D.handles.map(function (h) { return { label: h.label, body: h.body, s: h.s }; });
      for (const p of D.scene.pins) {
        const i = D.bodyIndex[p.body_i] ? 1 : 0;
        const body = i ? p.body_i : p.body_j, s = i ? p.s_i : p.s_j;
        if (!D.bodyIndex[body]) continue;
        if (!out.some(function (o) { return o.label === p.name; })) out.push({ label: p.name, body: body, s: s });
      }
      return out;
    }
    function pickAt(X, Y) {
      const k = shownRow(frame);
      if (k < 0) return null;
      let best = null, bd = 9;
      for (const h of pickables()) {
        const g = place(pose(D.bodyIndex[h.body], k), h.s), s = toScreen(g[0], g[1]), d = Math.max(Math.abs(s[0] - X), Math.abs(s[1] - Y));
        if (d <= bd) { bd = d; best = h; }
      }
      return best;
    }
    function pick(pk) {
      picked = pk;
      if (pk && !pointMotion(pk, 0) && api.onNeed) api.onNeed();
      render();
    }

    function handlePos(h, k) { return place(pose(D.bodyIndex[h.body], k), h.s); }

    function drawHandles(k) {
      if (!api.onEdit) return;
      for (const h of D.handles) {
        const g = handlePos(h, k), s = toScreen(g[0], g[1]);
        const on = (hover && hover.id === h.id) || (drag && drag.handle.id === h.id);
        ctx.strokeStyle = on ? "#d62728" : "#1f4e79"; ctx.lineWidth = on ? 2 : 1.2;
        ctx.strokeRect(s[0] - 6.5, s[1] - 6.5, 13, 13);
      }
    }

    function angleText(v) { return angleUnit === "deg" ? (v * 180 / Math.PI).toFixed(3) + "°" : v.toFixed(5) + " rad"; }
    function lengthText(v) { return lengthUnit === "mm" ? (v * 1000).toFixed(3) + " mm" : v.toFixed(6) + " m"; }

    function render() {
      if (!D) return;
      const t0 = performance.now();
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
      grid();
      const k = shownRow(frame);
      if (k >= 0) {
        drawScene(k);
        drawTraces(k);
        drawPins(k);
        drawForces(k);
        drawMarks();
        drawHandles(k);
        drawPicked(k);
      } else {
        setText(pickBox, "");
      }
      ctx.font = "12px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "top";
      let y = 6;
      if (D.ok && !D.ok[frame]) {
        ctx.fillStyle = "#d62728";
        ctx.fillText("does not assemble at t = " + D.t[frame].toFixed(4) + " s" + (k >= 0 ? " (nearest assembled time shown)" : ""), 40, y);
        y += 16;
      }
      ctx.fillStyle = "#333";
      for (const c of D.cams) {
        const v = channel(c + ".phi");
        if (v && k >= 0) { ctx.fillText("cam " + c + ": " + angleText(v[k]), 40, y); y += 16; }
      }
      setText(timeLabel, "t = " + D.t[frame].toFixed(4) + " s");
      if (slider.value !== String(frame)) slider.value = String(frame);
      for (const p of plots) p.cursor();
      updateReadout();
      const dt = performance.now() - t0;
      stats.frames += 1; stats.renderMs += dt; stats.lastDraw = performance.now();
    }

    function updateReadout() {
      const lines = [];
      const k = shownRow(frame);
      if (hover && k >= 0) {
        const g = handlePos(hover, k);
        lines.push(hover.label + ": x = " + lengthText(g[0]) + ", y = " + lengthText(g[1]));
        const b = D.bodyIndex[hover.body];
        if (b > 0) { const q = pose(b, k); lines.push(hover.body + ": x = " + lengthText(q[0]) + ", y = " + lengthText(q[1]) + ", φ = " + angleText(q[2])); }
      }
      setText(readout, lines.join("\n"));
    }

    // -- time -----------------------------------------------------------
    function rowAt(tt) {
      const t = D.t; let lo = 0, hi = D.rows - 1;
      while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (t[mid] <= tt) lo = mid; else hi = mid; }
      return (tt - t[lo] <= t[hi] - tt) ? lo : hi;
    }
    function seek(tt) { simTime = tt; frame = rowAt(tt); render(); }
    function setFrame(k) { frame = Math.max(0, Math.min(D.rows - 1, k)); simTime = D.t[frame]; render(); }
    function togglePlay() {
      playing = !playing; last = null;
      play.textContent = playing ? "pause" : "play";
      if (playing) requestAnimationFrame(tick);
    }
    function tick(now) {
      if (!playing) return;
      const t = D.t, end = t[D.rows - 1];
      if (last !== null) {
        simTime += (now - last) / 1000 * speed;
        if (simTime > end) simTime = t[0] + (simTime - end) % ((end - t[0]) || 1);
        frame = rowAt(simTime);
      }
      last = now;
      render();
      requestAnimationFrame(tick);
    }
    slider.addEventListener("input", function () { setFrame(parseInt(slider.value, 10)); });
    speedSel.addEventListener("change", function () { speed = parseFloat(speedSel.value); });
    play.addEventListener("click", togglePlay);
    lengthSel.addEventListener("change", function () { lengthUnit = lengthSel.value; render(); });
    angleSel.addEventListener("change", function () { angleUnit = angleSel.value; for (const p of plots) p.remake(); render(); });
    fitBtn.addEventListener("click", function () { fit(); render(); });
    document.addEventListener("keydown", function (ev) {
      const tag = ev.target && ev.target.tagName;
      if (tag === "INPUT" && ev.target.type !== "range" || tag === "TEXTAREA") return;
      if (!D) return;
      if (ev.key === " ") { ev.preventDefault(); togglePlay(); }
      else if (ev.key === "ArrowRight" || ev.key === "ArrowLeft") {
        ev.preventDefault();
        const n = (ev.shiftKey ? 10 : 1) * (ev.key === "ArrowRight" ? 1 : -1);
        setFrame((frame + n + D.rows) % D.rows);
      }
    });

    // -- pointer: drag a handle, pan on empty space, wheel zoom ----------
    // Page (CSS px) to stage coordinates, inside the canvas's border.
    function origin() { const r = stage.getBoundingClientRect(); return [r.left + stage.clientLeft, r.top + stage.clientTop]; }
    function local(ev) { const o = origin(); return [ev.clientX - o[0], ev.clientY - o[1]]; }
    function handleAt(X, Y) {
      const k = shownRow(frame);
      if (k < 0) return null;
      let best = null, bd = 9;
      for (const h of D.handles) {
        const g = handlePos(h, k), s = toScreen(g[0], g[1]), d = Math.max(Math.abs(s[0] - X), Math.abs(s[1] - Y));
        if (d <= bd) { bd = d; best = h; }
      }
      return best;
    }
    stage.addEventListener("pointerdown", function (ev) {
      if (!D) return;
      const [X, Y] = local(ev);
      const h = api.onEdit ? handleAt(X, Y) : null;
      stage.setPointerCapture(ev.pointerId);
      if (h) {
        const g = handlePos(h, shownRow(frame)), s = toScreen(g[0], g[1]);
        drag = { handle: h, dx: s[0] - X, dy: s[1] - Y, row: shownRow(frame), gesture: "drag" + Date.now() + Math.random(), moved: false, X: X, Y: Y };
      } else {
        panning = { X: X, Y: Y, ox: ox, oy: oy, moved: false };
      }
    });
    stage.addEventListener("pointermove", function (ev) {
      if (!D) return;
      const [X, Y] = local(ev);
      if (drag) {
        if (!drag.moved && Math.max(Math.abs(X - drag.X), Math.abs(Y - drag.Y)) < 2) return;
        drag.moved = true;
        const w = toWorld(X + drag.dx, Y + drag.dy);
        api.onEdit({ op: "move", handle: drag.handle.id, row: drag.row, x: w[0], y: w[1], gesture: drag.gesture });
        return;
      }
      if (panning) {
        if (!panning.moved && Math.max(Math.abs(X - panning.X), Math.abs(Y - panning.Y)) < 2) return;
        panning.moved = true;
        ox = panning.ox + X - panning.X; oy = panning.oy + Y - panning.Y; render(); return;
      }
      const h = handleAt(X, Y);
      if (h !== hover) { hover = h; stage.style.cursor = h && api.onEdit ? "move" : "default"; render(); }
    });
    function release(ev) {
      // A click without a move picks the point under it (or none).
      if (drag && !drag.moved) pick({ label: drag.handle.label, body: drag.handle.body, s: drag.handle.s });
      else if (drag && api.onEditEnd) api.onEditEnd(drag.gesture);
      if (panning && !panning.moved && ev.type === "pointerup") { const [X, Y] = local(ev); pick(pickAt(X, Y)); }
      drag = null; panning = null;
      try { stage.releasePointerCapture(ev.pointerId); } catch (e) { /* not captured */ }
    }
    stage.addEventListener("pointerup", release);
    stage.addEventListener("pointercancel", release);
    stage.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      const [X, Y] = local(ev), f = Math.exp(-ev.deltaY * 0.0015);
      const w = toWorld(X, Y);
      scale *= f; ox = X - w[0] * scale; oy = Y + w[1] * scale;
      render();
    }, { passive: false });

    // -- plots ----------------------------------------------------------
    function isAngle(name) { const u = D.channels.units[D.index[name]]; return u && u.indexOf("rad") === 0; }
    function shownUnit(name) {
      const u = D.channels.units[D.index[name]] || "";
      return isAngle(name) && angleUnit === "deg" ? u.replace("rad", "°") : u;
    }
    // The plotted values of channel `name` (null where not assembled),
    // written into `out` when it is an array of the right length.
    function series(name, out) {
      const v = channel(name), k = isAngle(name) && angleUnit === "deg" ? 180 / Math.PI : 1;
      if (!out || out.length !== D.rows) out = new Array(D.rows);
      if (!v) {
        // Not sent: ask for it (the studio), shown empty until it comes.
        if (api.onNeed) api.onNeed();
        return out.fill(null);
      }
      for (let i = 0; i < D.rows; i++) out[i] = v[i] === v[i] ? v[i] * k : null;
      return out;
    }
    // The times as a plot's x values, in `out` when it has the right length.
    function times(out) {
      if (!out || out.length !== D.rows) return Array.from(D.t);
      for (let i = 0; i < D.rows; i++) out[i] = D.t[i];
      return out;
    }
    function newPlot(name) {
      const box = el("div", "cl-plot");
      const head = el("div", "cl-plothead");
      const pick = el("select", "cl-pick");
      for (const nm of D.channels.names) { const o = el("option", null, nm); o.value = nm; pick.appendChild(o); }
      pick.value = name;
      const unitLabel = el("span", "cl-unit");
      const value = el("span", "cl-value");
      head.appendChild(pick); head.appendChild(unitLabel); head.appendChild(value);
      box.appendChild(head);
      plotsBox.appendChild(box);
      const p = { name: name, box: box, value: value, u: null, names: D.channels.names.join("\n") };
      function make() {
        if (p.u) { p.u.destroy(); p.u = null; }
        unitLabel.textContent = " (" + (shownUnit(p.name) || "–") + ") against t (s)";
        const opts = {
          width: opts2.width, height: opts2.height,
          legend: { show: false },
          cursor: { drag: { x: false, y: false } },
          scales: { x: { time: false } },
          axes: [{ label: "t (s)", size: 34, labelSize: 14 }, { size: 54 }],
          series: [{}, { stroke: "#1f4e79", width: 1.4, spanGaps: false }],
          hooks: {
            setCursor: [function (u) {
              const i = u.cursor.idx;
              if (i === null || i === undefined) { showValue(frame); return; }
              showValue(i);
            }],
            drawClear: [function (u) {
              if (!D.ok) return;
              const g = u.ctx; g.save(); g.fillStyle = "rgba(214,39,40,0.12)";
              for (let i = 0; i < D.rows; i++) {
                if (D.ok[i]) continue;
                const a = u.valToPos(D.t[Math.max(0, i - 0.5 | 0)], "x", true), b = u.valToPos(D.t[Math.min(D.rows - 1, i + 1)], "x", true);
                g.fillRect(a, u.bbox.top, Math.max(1, b - a), u.bbox.height);
              }
              g.restore();
            }],
            draw: [function (u) {
              const X = u.valToPos(D.t[frame], "x", true), g = u.ctx;
              g.save(); g.strokeStyle = "#555"; g.lineWidth = dpr; g.setLineDash([4 * dpr, 3 * dpr]);
              for (const m of D.marks) {
                const Xm = u.valToPos(m.t, "x", true);
                g.beginPath(); g.moveTo(Xm, u.bbox.top); g.lineTo(Xm, u.bbox.top + u.bbox.height); g.stroke();
              }
              g.restore();
              g.save(); g.strokeStyle = "#d62728"; g.lineWidth = 1.5 * dpr; g.beginPath();
              g.moveTo(X, u.bbox.top); g.lineTo(X, u.bbox.top + u.bbox.height); g.stroke(); g.restore();
            }],
          },
        };
        p.data = [Array.from(D.t), series(p.name)];
        p.u = new uPlot(opts, p.data, box);
        p.u.over.addEventListener("click", function () {
          const i = p.u.cursor.idx;
          if (i !== null && i !== undefined) setFrame(i);
        });
        p.u.root.dataset.channel = p.name;
        p.u.ctx.canvas.classList.add("plot");
      }
      function showValue(i) {
        const v = p.data[1][i];
        setText(p.value, " t = " + D.t[i].toFixed(4) + " s: " + (v === null ? "not assembled" : Number(v).toPrecision(7) + " " + shownUnit(p.name)));
        p.value.dataset.row = String(i);
      }
      // New data: the same plot with new values when the channels are the
      // same; made again (and the picker refilled) when they are not.
      p.refresh = function () {
        if (!(p.name in D.index)) p.name = D.channels.names[0];
        const names = D.channels.names.join("\n");
        if (names !== p.names) {
          p.names = names;
          pick.textContent = "";
          for (const nm of D.channels.names) { const o = el("option", null, nm); o.value = nm; pick.appendChild(o); }
          pick.value = p.name;
          make();
          return;
        }
        // The arrays of the last data, refilled (no new arrays per edit).
        p.data = [times(p.data[0]), series(p.name, p.data[1])];
        p.u.setData(p.data);
      };
      p.cursor = function () { if (p.u) { p.u.redraw(false, false); if (p.u.cursor.idx === null || p.u.cursor.idx === undefined) showValue(frame); } };
      p.remake = make;
      pick.addEventListener("change", function () { p.name = pick.value; make(); });
      make();
      plots.push(p);
      return p;
    }
    const opts2 = { width: opts.plotWidth || 440, height: opts.plotHeight || 190 };
    addPlot.addEventListener("click", function () { if (D) newPlot(D.plots[0] || D.channels.names[0]); });

    api.setData = setData;
    // The channels the page shows: the plots', and the picked point's body's.
    api.picked = function () {
      const out = plots.map(function (p) { return p.name; });
      if (picked && D.bodyIndex[picked.body]) for (const c of ["vx", "vy", "omega", "ax", "ay", "alpha"]) out.push(picked.body + "." + c);
      return out;
    };
    api.pick = function (label) {
      const pk = label === null ? null : pickables().find(function (h) { return h.label === label; });
      pick(pk || null);
      return pk ? pk.label : null;
    };
    api.pickedPoint = function () { return picked; };
    api.render = render;
    api.seek = seek;
    api.setFrame = setFrame;
    api.frame = function () { return frame; };
    api.time = function () { return D.t[frame]; };
    api.rows = function () { return D ? D.rows : 0; };
    api.stats = stats;
    api.plots = plots;
    api.data = function () { return D; };
    api.channel = channel;
    api.pixel = function (x, y) { const o = origin(), s = toScreen(x, y); return [o[0] + s[0], o[1] + s[1]]; };
    api.world = function (X, Y) { const o = origin(); return toWorld(X - o[0], Y - o[1]); };
    api.scale = function () { return scale; };
    api.handle = function (id) {
      const h = D.handles.find(function (v) { return v.id === id; });
      return h ? handlePos(h, shownRow(frame)) : null;
    };
    api.plotPixel = function (n, i) {
      // Page position of row i on plot n's curve (CSS px).
      const u = plots[n].u, r = u.over.getBoundingClientRect(), v = plots[n].data[1][i];
      return [r.left + u.valToPos(D.t[i], "x"), r.top + (v === null ? 0 : u.valToPos(v, "y"))];
    };
    return api;
  }

  // The studio pages' link to their server: a websocket carrying the
  // page's requests ({op, …}, numbered by `seq`) and the server's replies,
  // the undo/redo/save buttons and keys (Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y,
  // Ctrl+S), and the message line. `opts.reply(reply)` gets each reply,
  // `opts.before(msg)` may add to each request. `after(n)` is a promise of
  // the reply to request n having been handled (for scripts and benchmarks).
  function editor(opts) {
    const token = document.querySelector('meta[name="camlink-token"]').content;
    const message = document.getElementById("message");
    const waiting = {}, sentAt = {}, phases = {};
    let ws = null, seq = 0;
    // phases[n]: [ms from request n sent to its reply received, to parse
    // the reply, to show it, the server's share of the first] (for the
    // benchmark's breakdown).
    const api = { answered: 0, sentAt: sentAt, phases: phases };
    api.say = function (text, bad) { setText(message, text); message.classList.toggle("bad", !!bad); };
    api.send = function (msg) {
      seq += 1; msg.seq = seq; sentAt[seq] = performance.now();
      if (opts.before) opts.before(msg);
      ws.send(JSON.stringify(msg));
      return seq;
    };
    api.sent = function () { return seq; };
    api.after = function (n) {
      if (api.answered >= n) return Promise.resolve();
      return new Promise(function (resolve) { (waiting[n] = waiting[n] || []).push(resolve); });
    };
    api.shown = function (data) {
      setText(document.getElementById("title"), data.title);
      setText(document.getElementById("file"), data.file);
      setText(document.getElementById("dirty"), data.dirty ? "● unsaved" : "");
      if (document.title !== data.title + " · camlink studio") document.title = data.title + " · camlink studio";
      const undo = document.getElementById("undo"), redo = document.getElementById("redo");
      if (undo.disabled !== !data.undo) undo.disabled = !data.undo;
      if (redo.disabled !== !data.redo) redo.disabled = !data.redo;
    };
    document.getElementById("undo").addEventListener("click", function () { api.send({ op: "undo" }); });
    document.getElementById("redo").addEventListener("click", function () { api.send({ op: "redo" }); });
    document.getElementById("save").addEventListener("click", function () { api.send({ op: "save" }); });
    document.addEventListener("keydown", function (ev) {
      if ((ev.ctrlKey || ev.metaKey) && ev.key === "z") { ev.preventDefault(); api.send({ op: ev.shiftKey ? "redo" : "undo" }); }
      else if ((ev.ctrlKey || ev.metaKey) && ev.key === "y") { ev.preventDefault(); api.send({ op: "redo" }); }
      else if ((ev.ctrlKey || ev.metaKey) && ev.key === "s") { ev.preventDefault(); api.send({ op: "save" }); }
    });
    const url = (location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws?token=" + encodeURIComponent(token);
    ws = new WebSocket(url);
    ws.binaryType = "arraybuffer";
    ws.onopen = function () { api.send({ op: "hello", binary: true }); };
    ws.onclose = function () { api.say("disconnected from the server", true); };
    ws.onmessage = function (ev) {
      const t0 = performance.now();
      const reply = typeof ev.data === "string" ? JSON.parse(ev.data) : unpack(ev.data);
      const t1 = performance.now();
      if (reply.seq) api.answered = Math.max(api.answered, reply.seq);
      if (reply.type === "saved") {
        document.getElementById("dirty").textContent = reply.dirty ? "● unsaved" : "";
        api.say("saved " + reply.file + " (the previous file kept as " + reply.file + ".bak)");
      } else if (reply.type === "error") {
        api.say(reply.message, true);
      }
      opts.reply(reply);
      if (reply.seq && sentAt[reply.seq] !== undefined) {
        phases[reply.seq] = [t0 - sentAt[reply.seq], t1 - t0, performance.now() - t1, reply.server_ms];
      }
      for (const n of Object.keys(waiting)) {
        if (Number(n) <= api.answered) { for (const f of waiting[n]) f(); delete waiting[n]; }
      }
    };
    return api;
  }

  root.camlinkFront = { create: create, decode: decode, unpack: unpack, setText: setText, editor: editor, niceStep: niceStep, fmt: fmt };
})(window);
