// The studio page: the shared front end plus the edits, sent over a
// websocket to the server, which answers with the re-solved cycle.
"use strict";
(function () {
  const front = camlinkFront.create(document.getElementById("app"), { width: 720, height: 520 });
  const timing = { edits: 0, last: null, waits: [] };
  let params = [];
  const link = camlinkFront.editor({
    before: function (msg) { if (front.data()) msg.plots = front.picked(); },
    reply: function (reply) {
      if (reply.type === "frames") {
        show(reply.data);
        const t0 = link.sentAt[reply.seq];
        if (t0 !== undefined) timing.last = performance.now() - t0;
        if (reply.data.error) link.say(reply.data.error, true);
        else if (reply.seq > 1) link.say("");
      }
      window.camlinkStudio.answered = link.answered;
    },
  });
  const send = link.send;

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
    link.shown(data);
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

  // For scripts and benchmarks: `after(n)` is a promise of the reply to
  // request `n` having been shown (the page redrawn).
  window.camlinkStudio = { front: front, send: send, timing: timing, answered: 0, after: link.after,
                           sent: link.sent };
})();
