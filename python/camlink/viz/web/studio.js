// The studio page: the shared front end plus the edits, sent over a
// websocket to the server, which answers with the re-solved cycle.
"use strict";
(function () {
  const token = document.querySelector('meta[name="camlink-token"]').content;
  const front = camlinkFront.create(document.getElementById("app"), { width: 720, height: 520 });
  const message = document.getElementById("message");
  let ws = null, seq = 0, answered = 0, sentAt = {};
  const timing = { edits: 0, last: null, waits: [] };
  let params = [];

  function say(text, bad) { message.textContent = text; message.classList.toggle("bad", !!bad); }
  function send(msg) {
    seq += 1; msg.seq = seq; sentAt[seq] = performance.now();
    if (front.data()) msg.plots = front.picked();
    ws.send(JSON.stringify(msg));
    return seq;
  }

  function sliders(list) {
    const box = document.getElementById("params");
    const same = list.length === params.length && list.every(function (p, i) { return p.name === params[i].name; });
    if (same) {
      list.forEach(function (p, i) {
        const input = box.querySelectorAll("input")[i], out = box.querySelectorAll("output")[i];
        if (document.activeElement !== input) { input.value = String(p.value); }
        out.textContent = String(p.value);
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

  function show(data) {
    document.getElementById("title").textContent = data.title;
    document.getElementById("file").textContent = data.file;
    document.getElementById("dirty").textContent = data.dirty ? "● unsaved" : "";
    document.title = data.title + " · camlink studio";
    document.getElementById("undo").disabled = !data.undo;
    document.getElementById("redo").disabled = !data.redo;
    front.setData(data);
    sliders(data.parameters);
  }

  // Every request names the channels the plots show: the reply carries
  // their values (and the poses and traces), not every channel's.
  front.onEdit = function (msg) { timing.edits += 1; send(msg); };
  let needed = false;
  front.onNeed = function () {
    if (needed) return;
    needed = true;
    setTimeout(function () { needed = false; send({ op: "hello" }); }, 0);
  };
  front.onEditEnd = function (gesture) { send({ op: "end", gesture: gesture }); };
  document.getElementById("undo").addEventListener("click", function () { send({ op: "undo" }); });
  document.getElementById("redo").addEventListener("click", function () { send({ op: "redo" }); });
  document.getElementById("save").addEventListener("click", function () { send({ op: "save" }); });
  document.addEventListener("keydown", function (ev) {
    if ((ev.ctrlKey || ev.metaKey) && ev.key === "z") { ev.preventDefault(); send({ op: ev.shiftKey ? "redo" : "undo" }); }
    else if ((ev.ctrlKey || ev.metaKey) && ev.key === "y") { ev.preventDefault(); send({ op: "redo" }); }
    else if ((ev.ctrlKey || ev.metaKey) && ev.key === "s") { ev.preventDefault(); send({ op: "save" }); }
  });

  const url = (location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws?token=" + encodeURIComponent(token);
  ws = new WebSocket(url);
  ws.onopen = function () { send({ op: "hello" }); };
  ws.onclose = function () { say("disconnected from the server", true); };
  ws.onmessage = function (ev) {
    const reply = JSON.parse(ev.data);
    if (reply.seq) answered = Math.max(answered, reply.seq);
    if (reply.type === "frames") {
      show(reply.data);
      const t0 = sentAt[reply.seq];
      if (t0 !== undefined) timing.last = performance.now() - t0;
      if (reply.data.error) say(reply.data.error, true);
      else if (reply.seq > 1) say("");
    } else if (reply.type === "saved") {
      document.getElementById("dirty").textContent = reply.dirty ? "● unsaved" : "";
      say("saved " + reply.file + " (the previous file kept as " + reply.file + ".bak)");
    } else if (reply.type === "error") {
      say(reply.message, true);
    }
    window.camlinkStudio.answered = answered;
    for (const n of Object.keys(waiting)) {
      if (Number(n) <= answered) { for (const f of waiting[n]) f(); delete waiting[n]; }
    }
  };

  // For scripts and benchmarks: a promise of the reply to request `n`
  // having been shown (the page redrawn).
  const waiting = {};
  function after(n) {
    if (answered >= n) return Promise.resolve();
    return new Promise(function (resolve) { (waiting[n] = waiting[n] || []).push(resolve); });
  }
  window.camlinkStudio = { front: front, send: send, timing: timing, answered: 0, after: after,
                           sent: function () { return seq; } };
})();
