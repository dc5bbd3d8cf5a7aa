// The studio page: the shared front end plus the edits, sent over a
// websocket to the server, which answers with the re-solved cycle.
"use strict";
(function () {
  const front = camlinkFront.create(document.getElementById("app"), { width: 720, height: 520 });
  // edits: made on the page; sent: sent to the server (edits and their ends).
  const timing = { edits: 0, sent: 0, last: null, waits: [] };
  let params = [];
  const link = camlinkFront.editor({
    before: function (msg) { if (front.data()) msg.plots = front.picked(); },
    reply: function (reply) {
      if (reply.type === "run") runStatus(reply);
      else if (reply.type === "runchannel") runPlot(reply.name, camlinkFront.decode(reply.values));
      if (reply.type === "frames") {
        show(reply.data, reply.seq);
        const t0 = link.sentAt[reply.seq];
        if (t0 !== undefined) timing.last = performance.now() - t0;
        if (reply.data.error) link.say(reply.data.error, true);
        else if (reply.seq > 1) link.say("");
      }
      window.camlinkStudio.answered = link.answered;
      editAnswered(reply.seq);
    },
  });
  const send = link.send;

  function sliders(list) {
    const box = document.getElementById("params");
    const same = list.length === params.length && list.every(function (p, i) { return p.name === params[i].name; });
    if (same) {
      list.forEach(function (p, i) {
        const input = box.querySelectorAll("input")[i], out = box.querySelectorAll("output")[i];
        if (document.activeElement !== input && input.value !== String(p.value)) input.value = String(p.value);
        camlinkFront.setText(out, String(p.value));
      });
      params = list;
      return;
    }
    params = list;
    box.textContent = "";
    for (const p of list) {
      const label = document.createElement("label");
      const name = document.createElement("span"); name.textContent = p.name;
      const input = document.createElement("input");
      input.type = "range"; input.min = String(p.min); input.max = String(p.max);
      input.step = "any"; input.value = String(p.value);
      input.dataset.name = p.name;
      const out = document.createElement("output"); out.textContent = String(p.value);
      let gesture = null;
      input.addEventListener("input", function () {
        if (gesture === null) gesture = "param" + Date.now() + Math.random();
        out.textContent = input.value;
        front.onEdit({ op: "param", name: p.name, value: parseFloat(input.value), gesture: gesture });
      });
      input.addEventListener("change", function () { front.onEditEnd(gesture); gesture = null; });
      label.appendChild(name); label.appendChild(input); label.appendChild(out);
      box.appendChild(label);
    }
  }

  // -- analyses run from the page: started, followed and stopped here,
  // run by the server in a thread of its own; the finished run's channels
  // plotted against t. Messages may arrive out of order: the highest
  // numbered (run id, then n) wins.
  const RUN = { id: 0, n: 0, state: "idle", done: 0, total: 0, t: null, names: [], units: {},
                channel: null, values: null, plot: null };
  const pickRun = document.getElementById("run-analysis");
  let analysisSet = false;
  const pickChannel = document.getElementById("run-channel");
  document.getElementById("run").addEventListener("click", function () { send({ op: "run", analysis: pickRun.value }); });
  document.getElementById("stop").addEventListener("click", function () { send({ op: "stop" }); });
  pickChannel.addEventListener("change", function () { send({ op: "runchannel", name: pickChannel.value }); });
  function runStatus(r) {
    if (r.id < RUN.id || (r.id === RUN.id && r.n < RUN.n)) return;
    RUN.id = r.id; RUN.n = r.n; RUN.state = r.state; RUN.done = r.done; RUN.total = r.total;
    const bar = document.getElementById("run-progress"), status = document.getElementById("run-status");
    bar.max = Math.max(1, r.total); bar.value = r.done;
    document.getElementById("run").disabled = r.state === "running";
    document.getElementById("stop").disabled = r.state !== "running";
    const unit = r.analysis === "study" ? " variants" : " rows";
    status.textContent = r.state === "running" ? r.analysis.replace("_", " ") + ": " + r.done + " of " + r.total + unit : r.message;
    status.dataset.state = r.state;
    studyTable(r.table);
    if (!r.names) return;
    RUN.t = camlinkFront.decode(r.t); RUN.names = r.names; RUN.units = r.units;
    pickChannel.textContent = "";
    for (const nm of r.names) { if (nm === "t") continue; const o = document.createElement("option"); o.value = nm; o.textContent = nm; pickChannel.appendChild(o); }
    pickChannel.hidden = false;
    const given = Object.keys(r.channels);
    const first = given.length ? given[0] : r.names.find(function (nm) { return nm !== "t"; });
    pickChannel.value = first;
    if (given.length) runPlot(first, camlinkFront.decode(r.channels[first]));
    else send({ op: "runchannel", name: first });
  }
  // A study's table: one row per variant, parameters, outputs, status.
  function studyTable(table) {
    const box = document.getElementById("study");
    RUN.table = table || null;
    box.textContent = "";
    if (!table) return;
    const t = document.createElement("table"), head = document.createElement("tr");
    for (const c of table.columns) { const th = document.createElement("th"); th.textContent = c; head.appendChild(th); }
    t.appendChild(head);
    for (const row of table.rows) {
      const tr = document.createElement("tr");
      for (const v of row) {
        const td = document.createElement("td");
        td.textContent = v === null ? "–" : typeof v === "number" && !Number.isInteger(v) ? v.toPrecision(7) : String(v);
        tr.appendChild(td);
      }
      t.appendChild(tr);
    }
    box.appendChild(t);
  }
  function runPlot(name, values) {
    RUN.channel = name; RUN.values = values;
    const box = document.getElementById("run-plot");
    if (RUN.plot) { RUN.plot.destroy(); RUN.plot = null; }
    const unitText = RUN.units[name] ? " (" + RUN.units[name] + ")" : "";
    RUN.plot = new uPlot({
      width: 720, height: 180, legend: { show: false }, scales: { x: { time: false } },
      axes: [{ label: "t (s)", size: 34, labelSize: 14 }, { label: name + unitText, size: 64, labelSize: 14 }],
      series: [{}, { stroke: "#b07aa1", width: 1.4 }],
      hooks: { setCursor: [function (u) {
        const i = u.cursor.idx;
        document.getElementById("run-value").textContent = (i === null || i === undefined) ? "" :
          "t = " + RUN.t[i].toFixed(4) + " s: " + Number(values[i]).toPrecision(7) + unitText;
      }] },
    }, [Array.from(RUN.t), Array.from(values)], box);
  }

  // -- motion programs of `motion` curves: cells edited are staged and
  // applied together (a rise and its return: a program that does not
  // close is refused), as numbers or expressions of the parameters.
  const staged = {};
  let motionKey = "", applying = 0;
  const applyButton = document.getElementById("motion-apply");
  function stage(input, seg, key) {
    const id = seg.curve + "\n" + seg.index + "\n" + key, text = input.value.trim();
    const number = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(text);
    staged[id] = { curve: seg.curve, index: seg.index, key: key, value: number ? Number(text) : text };
    input.classList.add("staged");
    applyButton.disabled = false;
  }
  applyButton.addEventListener("click", function () {
    const changes = Object.keys(staged).map(function (id) { return staged[id]; });
    if (changes.length) applying = send({ op: "segments", changes: changes });
  });
  function motion(list, seq) {
    const box = document.getElementById("motion"), body = box.querySelector("tbody");
    if (box.hidden !== (list.length === 0)) box.hidden = list.length === 0;
    if (seq === applying && applying) {
      for (const id of Object.keys(staged)) delete staged[id];
      applyButton.disabled = true;
    }
    const key = list.map(function (g) { return g.curve + "/" + g.index; }).join(",");
    if (key !== motionKey) {
      motionKey = key;
      body.textContent = "";
      for (const g of list) {
        const tr = document.createElement("tr");
        for (const text of [g.curve, String(g.index)]) { const td = document.createElement("td"); td.textContent = text; tr.appendChild(td); }
        for (const k of ["law", "span", "lift"]) {
          const td = document.createElement("td"), input = document.createElement("input");
          input.type = "text"; input.dataset.curve = g.curve; input.dataset.index = String(g.index); input.dataset.key = k;
          input.addEventListener("change", function () { stage(input, g, k); });
          td.appendChild(input); tr.appendChild(td);
        }
        body.appendChild(tr);
      }
    }
    if (!list.length) return;
    body.querySelectorAll("input").forEach(function (input) {
      const g = list.find(function (v) { return v.curve === input.dataset.curve && String(v.index) === input.dataset.index; });
      const id = g.curve + "\n" + g.index + "\n" + input.dataset.key;
      if (staged[id]) return;
      input.classList.remove("staged");
      if (document.activeElement !== input) input.value = String(g[input.dataset.key]);
    });
  }

  function show(data, seq) {
    link.shown(data);
    motion(data.segments || [], seq);
    if (data.analyses) {
      // The analyses the core runs (sent with the first frames), before
      // the studies beside the file.
      pickRun.querySelectorAll("option.analysis").forEach(function (o) { o.remove(); });
      for (const a of data.analyses) {
        const o = document.createElement("option"); o.className = "analysis"; o.value = a;
        o.textContent = a.replace("_", " "); pickRun.appendChild(o);
      }
    }
    if (!analysisSet) { pickRun.value = data.analysis; analysisSet = true; }
    if (data.studies) {
      pickRun.querySelectorAll("option.study").forEach(function (o) { o.remove(); });
      for (const name of data.studies) {
        const o = document.createElement("option"); o.className = "study"; o.value = "study:" + name;
        o.textContent = "study " + name; pickRun.appendChild(o);
      }
    }
    front.setData(data);
    sliders(data.parameters);
  }

  // One edit in flight at a time: an edit made while another is being
  // solved waits, replacing a waiting edit of the same handle or
  // parameter in the same gesture, so a fast drag never queues positions behind old ones and
  // each reply shows the latest. The end of a drag or a slider move waits
  // behind its edits (it must reach the server after them).
  const waitingEdits = new Map();
  let inFlight = 0;
  function edit(msg) {
    const key = msg.op + "\n" + (msg.handle || msg.name || "") + "\n" + msg.gesture;
    if (inFlight || waitingEdits.size) {
      waitingEdits.delete(key);  // the newer goes last
      waitingEdits.set(key, msg);
      if (!inFlight) nextEdit();
      return;
    }
    inFlight = send(msg); timing.sent += 1;
    if (msg.op === "end") inFlight = 0;
  }
  function nextEdit() {
    while (!inFlight && waitingEdits.size) {
      const [key, msg] = waitingEdits.entries().next().value;
      waitingEdits.delete(key);
      inFlight = send(msg); timing.sent += 1;
      if (msg.op === "end") inFlight = 0;
    }
  }
  function editAnswered(seq) {
    if (seq && seq === inFlight) { inFlight = 0; nextEdit(); }
  }
  front.onEdit = function (msg) { timing.edits += 1; edit(msg); };
  // Every request names the channels the plots show: the reply carries
  // their values (and the poses and traces), not every channel's.
  let needed = false;
  front.onNeed = function () {
    if (needed) return;
    needed = true;
    setTimeout(function () { needed = false; send({ op: "hello" }); }, 0);
  };
  front.onEditEnd = function (gesture) { edit({ op: "end", gesture: gesture }); };

  // For scripts and benchmarks: `after(n)` is a promise of the reply to
  // request `n` having been shown (the page redrawn).
  window.camlinkStudio = { front: front, send: send, timing: timing, answered: 0, after: link.after, phases: link.phases,
                           sent: link.sent, run: function () { return RUN; } };
})();
