// VLNVerse-rs web app: Drive, Replay, Review. Plain JavaScript, no build step, no network
// beyond this server.
"use strict";

const $ = (id) => document.getElementById(id);
let INFO = null;

async function getJSON(url, opts) {
  const r = await fetch(url, opts);
  const body = await r.json().catch(() => ({ error: `${r.status} ${r.statusText}` }));
  if (!r.ok) throw new Error(body.error || `${r.status} ${r.statusText}`);
  return body;
}

function fill(select, values, label) {
  select.innerHTML = "";
  for (const v of values) {
    const o = document.createElement("option");
    o.value = typeof v === "object" ? v.value : v;
    o.textContent = typeof v === "object" ? v.label : (label ? label(v) : v);
    select.appendChild(o);
  }
}

function showMode(mode) {
  for (const m of ["drive", "replay", "review"]) {
    $(`mode-${m}`).classList.toggle("hidden", m !== mode);
    $(`tab-${m}`).classList.toggle("active", m === mode);
  }
  if (location.hash !== `#${mode}`) history.replaceState(null, "", `#${mode}`);
  if (mode === "replay") Replay.init();
  if (mode === "review") Review.init();
}

function fmt(v, d = 2) {
  if (v === null || v === undefined || v === "") return "-";
  return typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toFixed(d)) : String(v);
}

// ---------------------------------------------------------------- Drive
const Drive = {
  socket: null,
  state: null,
  frames: 0,
  fps: 0,
  inflight: 0,
  lastUrl: null,
  fpsWindow: [],

  init() {
    const tasks = [...new Set(INFO.splits.map((s) => s.task))];
    fill($("d-task"), tasks);
    fill($("d-setting"), INFO.settings);
    fill($("d-profile"), INFO.profiles);
    $("d-task").onchange = () => this.splits();
    $("d-split").onchange = () => this.episodes();
    $("d-start").onclick = () => this.start();
    $("d-depth").onchange = () => this.send({ view: $("d-depth").checked ? "depth" : "rgb" });
    $("d-ask-form").onsubmit = (e) => {
      e.preventDefault();
      const q = $("d-question").value.trim();
      if (q) this.send({ ask: q });
      $("d-question").value = "";
    };
    document.addEventListener("keydown", (e) => this.key(e));
    setInterval(() => this.tickFps(), 500);
    return this.splits();
  },

  splits() {
    const t = $("d-task").value;
    fill($("d-split"), INFO.splits.filter((s) => s.task === t).map((s) => s.split));
    return this.episodes();
  },

  async episodes() {
    const t = $("d-task").value, s = $("d-split").value;
    if (!t || !s) return;
    const seq = (this.seq = (this.seq || 0) + 1);
    const r = await getJSON(`/api/episodes?task=${t}&split=${s}`);
    if (seq !== this.seq) return; // a later choice of task or split won
    fill($("d-episode"), r.episodes.map((e) => ({ value: e.episode_id, label: `${e.episode_id} (${e.scene_id})` })));
  },

  async start() {
    if (this.socket) this.socket.close();
    this.socket = null;
    this.state = null;
    this.frames = 0;
    this.inflight = 0;
    this.fpsWindow = [];
    const t = $("d-task").value, s = $("d-split").value, id = $("d-episode").value;
    const ep = await getJSON(`/api/episode?task=${t}&split=${s}&id=${id}`);
    $("d-instruction").textContent = ep.instruction;
    $("d-ref").classList.toggle("hidden", !ep.has_reference_image);
    if (ep.has_reference_image) $("d-ref-img").src = `/api/reference-image?task=${t}&split=${s}&id=${id}`;
    $("d-dialogue").classList.toggle("hidden", ep.oracle_budget === null || ep.oracle_budget === undefined);
    $("d-answer").textContent = "";
    $("d-result").classList.add("hidden");
    $("d-depth").checked = false;
    const q = new URLSearchParams({ task: t, split: s, episode: id, setting: $("d-setting").value, profile: $("d-profile").value });
    const ws = new WebSocket(`ws://${location.host}/api/drive?${q}`);
    ws.binaryType = "blob";
    ws.onmessage = (m) => this.message(m);
    ws.onclose = () => { if (this.socket === ws) this.socket = null; };
    this.socket = ws;
    $("d-view").focus();
  },

  send(obj) {
    if (this.socket && this.socket.readyState === WebSocket.OPEN) {
      this.socket.send(JSON.stringify(obj));
      return true;
    }
    return false;
  },

  key(e) {
    if (!$("mode-drive").offsetParent) return;
    const tag = (e.target && e.target.tagName) || "";
    if (tag === "INPUT" || tag === "TEXTAREA" || tag === "SELECT") return;
    const k = e.key === " " ? "space" : e.key.toLowerCase();
    if (!["w", "a", "d", "q", "e", "space"].includes(k)) return;
    e.preventDefault();
    if (!this.state || this.state.done || this.inflight >= 3) return;
    if (this.send({ key: k })) this.inflight += 1;
  },

  message(m) {
    if (typeof m.data !== "string") {
      const url = URL.createObjectURL(m.data);
      $("d-view").src = url;
      if (this.lastUrl) URL.revokeObjectURL(this.lastUrl);
      this.lastUrl = url;
      this.frames += 1;
      this.fpsWindow.push(performance.now());
      return;
    }
    const msg = JSON.parse(m.data);
    if (msg.type === "error") {
      this.inflight = Math.max(0, this.inflight - 1);
      $("d-s-last").textContent = msg.error;
      return;
    }
    if (this.state) this.inflight = Math.max(0, this.inflight - 1);
    this.state = msg;
    $("d-s-setting").textContent = msg.setting;
    $("d-s-profile").textContent = msg.profile;
    $("d-s-step").textContent = `${msg.step} / ${msg.max_steps}`;
    $("d-s-coll").textContent = String(msg.collisions);
    $("d-s-last").textContent = msg.refused ? `refused: ${msg.refused}` : (msg.noticeable ? "collision!" : (msg.collided ? "touched" : "ok"));
    $("d-sub").classList.toggle("hidden", !msg.sub_instruction);
    if (msg.sub_instruction) $("d-sub").textContent = `Now (${msg.sub_goal + 1}/${msg.sub_goals}): ${msg.sub_instruction}`;
    if (msg.answer) $("d-answer").textContent = msg.answer;
    $("d-questions").textContent = `${msg.questions_left} question(s) left`;
    $("d-s-hint-row").classList.toggle("hidden", !("expert_key" in msg));
    if ("expert_key" in msg) $("d-s-hint").textContent = msg.expert_key;
    $("d-log").textContent = `log: ${msg.log}`;
    if (msg.done) {
      const r = $("d-result");
      const ok = msg.metrics && msg.metrics.success;
      r.className = `result ${ok ? "success" : "failure"}`;
      const m = msg.metrics || {};
      r.textContent = `${ok ? "Success" : "Failure"}${msg.failure ? " (" + msg.failure + ")" : ""}: NE ${fmt(m.ne)} m, SPL ${fmt(m.spl)}, nDTW ${fmt(m.ndtw)}, ${msg.step} steps, ${msg.collisions} collisions`;
    }
  },

  tickFps() {
    const now = performance.now();
    this.fpsWindow = this.fpsWindow.filter((t) => now - t < 2000);
    this.fps = this.fpsWindow.length / 2;
    $("d-fps").textContent = `${this.fps.toFixed(1)} frames/s (${this.frames} frames)`;
  },
};
window.vlnDrive = Drive;

// ---------------------------------------------------------------- Replay
const Replay = {
  ready: false,
  run: null,
  ep: null,
  step: 0,
  map: null,

  async init() {
    if (this.ready) return;
    this.ready = true;
    const r = await getJSON("/api/runs");
    this.runs = r.runs;
    fill($("r-run"), r.runs.map((x) => ({ value: x.index, label: `${x.name} (${x.agent}, ${x.task}/${x.split}, ${x.setting})` })));
    $("r-run").onchange = () => this.openRun(Number($("r-run").value));
    $("r-step").oninput = () => this.show(Number($("r-step").value));
    $("r-prev").onclick = () => this.show(this.step - 1);
    $("r-next").onclick = () => this.show(this.step + 1);
    document.addEventListener("keydown", (e) => {
      if (!$("mode-replay").offsetParent || !this.ep) return;
      if (e.key === "ArrowRight") { this.show(this.step + 1); e.preventDefault(); }
      if (e.key === "ArrowLeft") { this.show(this.step - 1); e.preventDefault(); }
    });
    if (r.runs.length) await this.openRun(r.runs[0].index);
  },

  async openRun(i) {
    this.run = i;
    const info = this.runs.find((x) => x.index === i);
    const s = info.summary || {};
    $("r-summary").textContent = `${s.episodes} episodes: SR ${fmt(s.sr)}, SPL ${fmt(s.spl)}, nDTW ${fmt(s.ndtw)}, CR ${fmt(s.cr)}`;
    const r = await getJSON(`/api/runs/${i}/episodes`);
    const t = $("r-episodes");
    t.innerHTML = "<tr><th>episode</th><th>success</th><th>NE</th><th>SPL</th><th>nDTW</th><th>steps</th></tr>";
    for (const e of r.episodes) {
      const tr = document.createElement("tr");
      tr.className = "ep";
      tr.dataset.id = e.episode_id;
      tr.innerHTML = `<td>${e.episode_id}</td><td>${e.success ? "yes" : "no"}</td><td>${fmt(e.ne)}</td><td>${fmt(e.spl)}</td><td>${fmt(e.ndtw)}</td><td>${fmt(e.steps)}</td>`;
      tr.onclick = () => this.openEpisode(e.episode_id);
      t.appendChild(tr);
    }
    if (r.episodes.length) await this.openEpisode(r.episodes[0].episode_id);
  },

  async openEpisode(id) {
    for (const tr of document.querySelectorAll("#r-episodes tr.ep")) tr.classList.toggle("selected", tr.dataset.id === String(id));
    const d = await getJSON(`/api/runs/${this.run}/episodes/${id}`);
    this.ep = d;
    $("r-instruction").textContent = d.episode.instruction;
    const n = d.trajectory.positions.length;
    $("r-step").max = String(n - 1);
    // Step 0 at once (the label and view must not show the previous episode while the
    // top-down picture renders); the map is drawn again when it arrives.
    this.map = new Image();
    this.map.onload = () => this.show(this.step);
    this.map.src = `/api/runs/${this.run}/episodes/${id}/topdown.png`;
    this.show(0);
  },

  show(k) {
    const d = this.ep;
    if (!d) return;
    const n = d.trajectory.positions.length;
    k = Math.max(0, Math.min(n - 1, k));
    this.step = k;
    $("r-step").value = String(k);
    $("r-step-label").textContent = `step ${k} / ${n - 1}`;
    $("r-view").src = `/api/runs/${this.run}/episodes/${d.episode.episode_id}/view/${k}`;
    // Every action but STOP adds a position, so a long-horizon sub-goal STOP shares its
    // position with the action after it.
    const at = d.trajectory.positions.map(() => []);
    let p = 0;
    for (const a of d.trajectory.actions || []) {
      if (p < at.length) at[p].push(a);
      if (a !== "stop") p += 1;
    }
    $("r-action").textContent = at[k].length ? `action at step ${k}: ${at[k].join(", then ")}` : "end of the trajectory";
    const c = $("r-map");
    if (this.map && this.map.complete && this.map.naturalWidth) {
      c.width = this.map.naturalWidth;
      c.height = this.map.naturalHeight;
      const g = c.getContext("2d");
      g.drawImage(this.map, 0, 0);
      const f = d.topdown;
      const p = d.trajectory.positions[k];
      const x = f.origin_px[0] + (p[0] - f.world_min[0]) * f.px_per_m;
      const y = f.origin_px[1] + (p[2] - f.world_min[1]) * f.px_per_m;
      const h = (d.trajectory.headings || [])[k];
      g.fillStyle = "#ff8c00";
      g.strokeStyle = "#222";
      g.lineWidth = 2;
      g.beginPath();
      g.arc(x, y, 7, 0, 2 * Math.PI);
      g.fill();
      g.stroke();
      if (h !== undefined) {
        // Yaw 0 looks along -Z (up in the picture); yaw grows counter-clockwise.
        g.beginPath();
        g.moveTo(x, y);
        g.lineTo(x - 18 * Math.sin(h), y - 18 * Math.cos(h));
        g.stroke();
      }
    }
  },
};
window.vlnReplay = Replay;

// ---------------------------------------------------------------- Review
const Review = {
  ready: false,
  list: [],
  i: 0,

  init() {
    if (this.ready) return;
    this.ready = true;
    const tasks = [...new Set(INFO.splits.map((s) => s.task))];
    fill($("v-task"), tasks);
    $("v-task").onchange = () => this.splits();
    $("v-split").onchange = () => this.load();
    $("v-prev").onclick = () => this.show(this.i - 1);
    $("v-next").onclick = () => this.show(this.i + 1);
    $("v-accept").onclick = () => this.decide("accepted");
    $("v-reject").onclick = () => this.decide("rejected");
    $("v-save-edit").onclick = () => this.decide("edited", $("v-edit").value);
    return this.splits();
  },

  splits() {
    const t = $("v-task").value;
    fill($("v-split"), INFO.splits.filter((s) => s.task === t).map((s) => s.split));
    return this.load();
  },

  async load() {
    const t = $("v-task").value, s = $("v-split").value;
    const seq = (this.seq = (this.seq || 0) + 1);
    const r = await getJSON(`/api/review/episodes?task=${t}&split=${s}`);
    if (seq !== this.seq) return; // a later choice of task or split won
    this.list = r.episodes;
    this.loaded = `${t}/${s}`;
    $("v-file").textContent = `decisions: ${r.review_file}`;
    this.show(0);
  },

  show(i) {
    if (!this.list.length) return;
    i = Math.max(0, Math.min(this.list.length - 1, i));
    this.i = i;
    const e = this.list[i];
    const t = $("v-task").value, s = $("v-split").value;
    $("v-pos").textContent = `${i + 1} / ${this.list.length}`;
    $("v-title").textContent = `Episode ${e.episode_id} (${e.scene_id}, ${fmt(e.geodesic_distance)} m${e.style ? ", " + e.style : ""})`;
    $("v-instruction").textContent = e.edited_instruction || e.instruction;
    $("v-edit").value = e.edited_instruction || e.instruction;
    const q = `task=${t}&split=${s}&id=${e.episode_id}`;
    $("v-start").src = `/api/review/view?${q}&at=start`;
    $("v-goal").src = `/api/review/view?${q}&at=goal`;
    $("v-map").src = `/api/review/topdown.png?${q}`;
    this.badge(e.decision);
    $("v-msg").textContent = "";
  },

  badge(d) {
    const b = $("v-decision");
    b.textContent = d || "undecided";
    b.className = `badge ${d || ""}`;
  },

  async decide(decision, text) {
    const e = this.list[this.i];
    const body = { task: $("v-task").value, split: $("v-split").value, episode_id: e.episode_id, decision };
    if (decision === "edited") body.instruction_text = text;
    try {
      const r = await getJSON("/api/review/decision", {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify(body),
      });
      e.decision = decision;
      e.edited_instruction = decision === "edited" ? text : null;
      this.badge(decision);
      $("v-msg").textContent = `saved (${r.decisions} decisions in ${r.review_file})`;
    } catch (err) {
      $("v-msg").textContent = String(err.message || err);
    }
  },
};
window.vlnReview = Review;

// ---------------------------------------------------------------- start
(async function main() {
  INFO = await getJSON("/api/info");
  $("dataset").textContent = INFO.dataset;
  for (const b of document.querySelectorAll(".tab")) b.onclick = () => showMode(b.dataset.mode);
  await Drive.init();
  const mode = (location.hash || "#drive").slice(1);
  showMode(["drive", "replay", "review"].includes(mode) ? mode : "drive");
  document.body.dataset.ready = "1";
})();
