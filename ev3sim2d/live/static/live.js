// The live page (`ev3sim2d live`, docs/live.md): draws the world and the robots from the latest state the
// server streams (GET api/events), at the screen's frame rate; its buttons and the hand on the canvas are
// the API's POSTs.  The world's drawing and the cell tools are the editor's (world_canvas.js).
// Everything comes from the live server itself (works offline).
"use strict";

(function () {
  const HANDLE = "rgb(213, 94, 0)";
  const PLOT_WINDOW_S = 10;
  const PLOT_KEPT = 20000; // samples kept per value
  const PLOT_COLORS = ["#56b4e9", "#e69f00", "#009e73", "#f0e442", "#cc79a7", "#d55e00", "#0072b2", "#ffffff"];
  const W = window.WorldCanvas;

  const canvas = document.getElementById("canvas");
  const ctx = canvas.getContext("2d");
  const plotCanvas = document.getElementById("plot");
  const plotCtx = plotCanvas.getContext("2d");
  let world = null; // GET api/world: the grid (cells), robot body, palette, world_version
  let latest = null; // the newest state
  let drawn = null; // the state the panel last showed
  let view = null;
  let tool = "robot";
  let gesture = null; // {kind: "move"|"rotate", robot, pose} or {kind: "cells", makeWall, last}
  let selected = 0; // the robot the keys turn
  let fetchingWorld = false;
  let run = -1;
  let series = new Map(); // key -> {label, samples: [[t, v]], on}
  let lastSampleT = -1;
  let plotChanged = true;
  const TRAIL_KEPT = 6000; // points kept per robot's trail
  let trails = []; // per robot: [x0, y0, x1, y1, ...] in cm, this run
  let worldLayer = null; // the cells drawn once, redrawn only when the world or the canvas changes
  let worldLayerKey = "";
  let panelShownAt = 0;
  const frameStats = { count: 0, drawMs: [] }; // for the benchmark (benchmarks/live_page.py)
  const bricks = new Map(); // robot number -> {leds, canvas, frame}
  let robotEdit = null; // GET api/robot: {robot, mapping, kinds, ports, file}

  function say(text, kind) {
    const box = document.getElementById("message");
    box.textContent = text;
    box.className = kind || "";
  }

  // -- talking to the server ----------------------------------------------------------------
  async function post(path, body) {
    try {
      const response = await window.PageToken.fetch(path, {
        method: "POST",
        headers: body === undefined ? {} : { "Content-Type": "application/json" },
        body: body === undefined ? undefined : JSON.stringify(body),
      });
      const answer = await response.json();
      if (!response.ok) {
        say(answer.error, "error");
        return null;
      }
      onState(answer);
      return answer;
    } catch (err) {
      say(`The live server did not answer (${err}). Is ev3sim2d live still running?`, "error");
      return null;
    }
  }

  async function loadWorld() {
    if (fetchingWorld) return;
    fetchingWorld = true;
    try {
      const response = await window.PageToken.fetch("api/world");
      const data = await response.json();
      if (!response.ok) return say(`Cannot load the world: ${data.error}`, "error");
      world = data;
      worldLayerKey = "";
      document.getElementById("title").textContent = data.title;
      document.title = `${data.title} – ev3sim2d live`;
    } catch (err) {
      say(`Cannot load the world: ${err}`, "error");
    } finally {
      fetchingWorld = false;
    }
  }

  function onState(state) {
    if (!state || !("t_s" in state)) return;
    latest = state;
    if (state.run !== run) {
      run = state.run;
      for (const s of series.values()) s.samples = [];
      lastSampleT = -1;
      trails = [];
      loadRobot(robotEdit ? robotEdit.robot : 1);
    }
    state.robots.forEach((r, i) => {
      const trail = trails[i] || (trails[i] = []);
      const n = trail.length;
      if (n && Math.abs(trail[n - 2] - r.x_cm) + Math.abs(trail[n - 1] - r.y_cm) < 0.3) return;
      trail.push(r.x_cm, r.y_cm);
      if (trail.length > 2 * TRAIL_KEPT) trail.splice(0, trail.length - 2 * TRAIL_KEPT);
    });
    if (world && state.world_version > world.world_version) loadWorld();
    sample(state);
  }

  function listen() {
    if (!window.PageToken.has()) {
      say("This page has no key: open the address ev3sim2d live printed in its terminal (it ends in #token=…).", "error");
      return;
    }
    window.PageToken.events(
      "api/events",
      (data) => onState(JSON.parse(data)),
      () => say("Connected. Drag a robot, click cells with a tool, or use the buttons."),
      () => say("Lost the live server; trying again…", "error"),
    );
  }

  // -- plots ------------------------------------------------------------------------------------
  function valuesOf(state) {
    const found = [];
    for (const robot of state.robots) {
      const who = state.robots.length > 1 ? `robot ${robot.number} ` : "";
      for (const sensor of robot.sensors) {
        sensor.values.forEach((v, i) => {
          const suffix = sensor.values.length > 1 ? `[${i}]` : "";
          const key = `${robot.number}/s/${sensor.port}/${i}`;
          found.push([key, `${who}${sensor.port} ${sensor.mode}${suffix}`, v, sensor.kind === "color" && i === 0]);
        });
      }
      for (const motor of robot.motors) {
        found.push([`${robot.number}/m/${motor.port}`, `${who}${motor.port} speed`, motor.speed, motor.kind === "large"]);
      }
    }
    return found;
  }

  function sample(state) {
    if (state.t_s === lastSampleT) return;
    lastSampleT = state.t_s;
    let added = false;
    for (const [key, label, value, shown] of valuesOf(state)) {
      let s = series.get(key);
      if (!s) {
        // at first: the colour sensors' first value and the large motors' speeds (a line follower's tuning)
        const on = shown && key.startsWith("1/") && [...series.values()].filter((x) => x.on).length < 4;
        s = { label: label, samples: [], on: on, color: PLOT_COLORS[series.size % PLOT_COLORS.length] };
        series.set(key, s);
        added = true;
      }
      s.label = label;
      if (typeof value === "number") {
        s.samples.push([state.t_s, value]);
        if (s.samples.length > PLOT_KEPT) s.samples.splice(0, s.samples.length - PLOT_KEPT);
      }
    }
    if (added) buildSeriesList();
    plotChanged = true;
  }

  function buildSeriesList() {
    const box = document.getElementById("series");
    box.textContent = "";
    for (const [key, s] of series) {
      const label = document.createElement("label");
      const check = document.createElement("input");
      check.type = "checkbox";
      check.checked = s.on;
      check.dataset.key = key;
      check.addEventListener("change", () => { s.on = check.checked; plotChanged = true; });
      const swatch = document.createElement("span");
      swatch.className = "swatch";
      swatch.style.background = s.color;
      label.append(check, swatch, document.createTextNode(s.label));
      box.append(label);
    }
  }

  function drawPlot() {
    const box = plotCanvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(box.width * dpr)), h = Math.max(1, Math.round(box.height * dpr));
    if (plotCanvas.width !== w || plotCanvas.height !== h) { plotCanvas.width = w; plotCanvas.height = h; plotChanged = true; }
    if (!plotChanged) return;
    plotChanged = false;
    const c = plotCtx;
    c.setTransform(1, 0, 0, 1, 0, 0);
    c.fillStyle = "rgb(22, 23, 27)";
    c.fillRect(0, 0, w, h);
    const on = [...series.values()].filter((s) => s.on && s.samples.length);
    const tEnd = Math.max(PLOT_WINDOW_S, latest ? latest.t_s : 0);
    const tStart = tEnd - PLOT_WINDOW_S;
    let lo = Infinity, hi = -Infinity;
    for (const s of on) for (const [t, v] of s.samples) if (t >= tStart) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi - lo < 1e-9) { hi += 1; lo -= 1; }
    const pad = 6 * dpr, left = 40 * dpr;
    const x = (t) => left + ((t - tStart) / PLOT_WINDOW_S) * (w - left - pad);
    const y = (v) => h - pad - ((v - lo) / (hi - lo)) * (h - 2 * pad);
    c.font = `${10 * dpr}px ui-monospace, monospace`;
    c.fillStyle = "#999";
    c.textBaseline = "middle";
    c.fillText(fmt(hi), 2, y(hi));
    c.fillText(fmt(lo), 2, y(lo));
    c.strokeStyle = "rgb(60, 62, 70)";
    c.lineWidth = 1;
    c.beginPath();
    for (let t = Math.ceil(tStart); t <= tEnd; t++) { c.moveTo(x(t), pad); c.lineTo(x(t), h - pad); }
    c.stroke();
    c.lineWidth = 1.5 * dpr;
    for (const s of on) {
      c.strokeStyle = s.color;
      c.beginPath();
      let started = false;
      for (const [t, v] of s.samples) {
        if (t < tStart) continue;
        if (started) c.lineTo(x(t), y(v)); else { c.moveTo(x(t), y(v)); started = true; }
      }
      c.stroke();
    }
  }
  const fmt = (v) => (Math.abs(v) >= 100 ? v.toFixed(0) : v.toFixed(1));

  // -- the world --------------------------------------------------------------------------------
  function poses() {
    if (!latest) return [];
    return latest.robots.map((r, i) =>
      gesture && (gesture.kind === "move" || gesture.kind === "rotate") && gesture.robot === i
        ? gesture.pose
        : { x_cm: r.x_cm, y_cm: r.y_cm, heading_deg: r.heading_deg });
  }
  function handlePoint(pose) {
    const reach = world.robot.front_cm + 6;
    const a = (pose.heading_deg * Math.PI) / 180;
    return { x: pose.x_cm + reach * Math.cos(a), y: pose.y_cm + reach * Math.sin(a) };
  }

  function drawTrails() {
    ctx.lineWidth = Math.max(1, view.dpr * 1.5);
    ctx.lineJoin = "round";
    trails.forEach((trail, i) => {
      if (trail.length < 4) return;
      ctx.strokeStyle = PLOT_COLORS[(i + 1) % PLOT_COLORS.length];
      ctx.globalAlpha = 0.75;
      ctx.beginPath();
      ctx.moveTo(W.pxX(view, trail[0]), W.pxY(view, trail[1]));
      for (let k = 2; k < trail.length; k += 2) ctx.lineTo(W.pxX(view, trail[k]), W.pxY(view, trail[k + 1]));
      ctx.stroke();
      ctx.globalAlpha = 1;
    });
  }

  // how far a sensor that looks forward sees now, in cm (its reading), for its beam
  function beamCm(sensor) {
    const v = sensor.values[0];
    if (typeof v !== "number") return 20;
    if (sensor.mode === "US-DIST-CM") return v / 10;
    if (sensor.mode === "US-DIST-IN") return (v / 10) * 2.54;
    if (sensor.mode === "IR-PROX") return (v / 100) * 70;
    return 20;
  }

  // where each sensor sits: a spot on the floor for one that looks down, a beam for one that looks ahead
  function drawSensors(robot, pose) {
    const a = (pose.heading_deg * Math.PI) / 180;
    for (const s of robot.sensors) {
      if (s.radius_cm === undefined || s.kind === "gyro" || s.kind === "nxt-sound") continue;
      const b = a + (s.angle_deg * Math.PI) / 180;
      const x = pose.x_cm + s.radius_cm * Math.cos(b), y = pose.y_cm + s.radius_cm * Math.sin(b);
      const px = W.pxX(view, x), py = W.pxY(view, y);
      if (s.facing === "forward" && s.kind !== "touch") {
        const d = a + ((s.aim_deg || 0) * Math.PI) / 180;
        const reach = Math.max(0, Math.min(255, beamCm(s)));
        ctx.strokeStyle = "rgba(86, 180, 233, 0.8)";
        ctx.lineWidth = Math.max(1, view.dpr);
        ctx.beginPath();
        ctx.moveTo(px, py);
        ctx.lineTo(W.pxX(view, x + reach * Math.cos(d)), W.pxY(view, y + reach * Math.sin(d)));
        ctx.stroke();
      }
      ctx.fillStyle = s.facing === "down" ? "rgb(255, 255, 255)" : "rgb(86, 180, 233)";
      ctx.strokeStyle = "rgb(20, 20, 20)";
      ctx.lineWidth = Math.max(1, view.dpr);
      ctx.beginPath();
      ctx.arc(px, py, Math.max(2.5 * view.dpr, 0.8 * view.scale), 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
    }
  }

  function drawWorld() {
    if (!world) return;
    view = W.fit(canvas, world);
    const key = `${canvas.width}x${canvas.height}`;
    if (key !== worldLayerKey) {
      worldLayer = worldLayer || document.createElement("canvas");
      worldLayer.width = canvas.width;
      worldLayer.height = canvas.height;
      W.drawCells(worldLayer.getContext("2d"), view, world, world.palette);
      worldLayerKey = key;
    }
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(worldLayer, 0, 0);
    drawTrails();
    poses().forEach((pose, i) => {
      const robot = latest.robots[i];
      W.drawRobotBody(ctx, view, robot.body || world.robot, pose);
      drawSensors(robot, pose);
      if (latest.robots.length > 1) {
        ctx.fillStyle = "white";
        ctx.font = `bold ${Math.round(12 * view.dpr)}px ui-monospace, monospace`;
        ctx.fillText(String(i + 1), W.pxX(view, pose.x_cm) - 4 * view.dpr, W.pxY(view, pose.y_cm) + 4 * view.dpr);
      }
      if (tool === "robot" && i === selected) {
        const h = handlePoint(pose);
        ctx.strokeStyle = HANDLE;
        ctx.lineWidth = Math.max(1, view.dpr * 1.5);
        ctx.beginPath();
        ctx.moveTo(W.pxX(view, pose.x_cm), W.pxY(view, pose.y_cm));
        ctx.lineTo(W.pxX(view, h.x), W.pxY(view, h.y));
        ctx.stroke();
        ctx.fillStyle = HANDLE;
        ctx.beginPath();
        ctx.arc(W.pxX(view, h.x), W.pxY(view, h.y), Math.max(5 * view.dpr, 1.6 * view.scale), 0, 2 * Math.PI);
        ctx.fill();
      }
    });
  }

  function frame() {
    const started = performance.now();
    drawWorld();
    // the panel's tables at most 10 times a second (text that changes faster cannot be read anyway)
    if (latest && latest !== drawn && (started - panelShownAt > 100 || !drawn || latest.status !== drawn.status || latest.run !== drawn.run)) {
      drawn = latest;
      panelShownAt = started;
      showPanel(latest);
    }
    drawPlot();
    frameStats.count++;
    frameStats.drawMs.push(performance.now() - started);
    if (frameStats.drawMs.length > 2000) frameStats.drawMs.splice(0, 1000);
    requestAnimationFrame(frame);
  }

  // -- the panel --------------------------------------------------------------------------------
  function cellText(text) {
    const td = document.createElement("td");
    td.textContent = text;
    return td;
  }
  function table(head, rows) {
    const t = document.createElement("table");
    const tr = document.createElement("tr");
    for (const h of head) { const th = document.createElement("th"); th.textContent = h; tr.append(th); }
    t.append(tr);
    for (const row of rows) {
      const r = document.createElement("tr");
      row.forEach((v, i) => { const td = cellText(v); if (i === row.length - 1 || head[i] === "position") td.className = "values"; r.append(td); });
      t.append(r);
    }
    return t;
  }
  const num = (v) => (typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toFixed(2)) : String(v));

  function showPanel(state) {
    document.getElementById("clock").textContent = `t = ${state.t_s.toFixed(2)} s`;
    const badge = document.getElementById("status-badge");
    // a program stopped in its debugger (a prompt in the terminal that started live): the world waits
    const status = state.debugging ? `paused at ${state.debugging}` : state.status;
    badge.textContent = status + (state.interventions ? ` · ${state.interventions} by hand` : "");
    badge.className = `badge ${state.debugging ? "paused" : state.status}`;
    badge.title = state.debugging ? "stopped in the debugger: go on at its prompt, in the terminal" : "";
    const pause = document.getElementById("pause");
    pause.textContent = state.status === "running" ? "Pause" : "Resume";
    pause.disabled = state.status === "ended" || state.status === "starting" || Boolean(state.debugging);
    const speed = document.getElementById("speed");
    const want = state.speed === null ? "max" : String(state.speed);
    if (document.activeElement !== speed && speed.value !== want) {
      if (![...speed.options].some((o) => o.value === want)) speed.append(new Option(`×${want}`, want));
      speed.value = want;
    }
    const devices = document.getElementById("devices");
    devices.textContent = "";
    for (const robot of state.robots) {
      const h = document.createElement("div");
      h.className = "hint";
      h.textContent = `${robot.name} at (${robot.x_cm.toFixed(1)}, ${robot.y_cm.toFixed(1)}) cm, ${robot.heading_deg.toFixed(0)}°`;
      devices.append(h);
      if (robot.sensors.length) {
        devices.append(table(["sensor", "kind", "mode", "values"],
          robot.sensors.map((s) => [s.port, s.kind, s.mode || "", s.values.map(num).join(" ")])));
      }
      if (robot.motors.length) {
        devices.append(table(["motor", "kind", "state", "position", "speed"],
          robot.motors.map((m) => [m.port, m.kind, m.state || "", num(m.position), num(m.speed)])));
      }
    }
    showBricks(state);
    document.getElementById("apply-robot").disabled = !(state.status === "paused" || state.status === "ended");
    const printed = document.getElementById("printed");
    const atBottom = printed.scrollTop + printed.clientHeight >= printed.scrollHeight - 4;
    printed.textContent = "";
    for (const line of state.printed.slice(-100)) {
      const span = document.createElement("span");
      span.className = line.stream;
      const who = state.robots.length > 1 ? `[${line.robot}] ` : "";
      span.textContent = `${line.t_s.toFixed(2)}  ${who}${line.text}\n`;
      printed.append(span);
    }
    if (atBottom) printed.scrollTop = printed.scrollHeight;
    const box = document.getElementById("error");
    const error = state.error;
    box.hidden = !error;
    if (error) {
      const where = error.line ? `${error.file}:${error.line}` : error.file;
      document.getElementById("error-where").textContent = `${where}${state.robots.length > 1 ? ` (robot ${error.robot})` : ""}`;
      document.getElementById("error-text").textContent =
        `${error.type}: ${error.message} — fix the program and press Reload (or save it: it reloads by itself).`;
      document.getElementById("error-traceback").textContent = error.traceback || "";
    }
  }

  // -- the brick: its two lights (a red and a green LED each: their mix is the colour) and its screen
  const brightness = (b) => Math.max(0, Math.min(1, (b || 0) / 255));
  function ledColor(leds, side) {
    const red = brightness(leds[`${side}:red:brick-status`]), green = brightness(leds[`${side}:green:brick-status`]);
    if (red === 0 && green === 0) return "rgb(35, 35, 35)";
    return `rgb(${Math.round(255 * red)}, ${Math.round(255 * green)}, 0)`;
  }

  function showBricks(state) {
    const box = document.getElementById("bricks");
    for (const robot of state.robots) {
      let brick = bricks.get(robot.number);
      if (!brick) {
        const row = document.createElement("div");
        row.className = "brick";
        const leds = document.createElement("div");
        leds.className = "leds";
        const lights = {};
        for (const [side, name] of [["led0", "left"], ["led1", "right"]]) {
          const label = document.createElement("span");
          const swatch = document.createElement("span");
          swatch.className = "led";
          swatch.dataset.side = name;
          label.append(swatch, document.createTextNode(` ${name}`));
          leds.append(label);
          lights[side] = swatch;
        }
        const who = document.createElement("span");
        who.textContent = state.robots.length > 1 ? `robot ${robot.number}` : "";
        leds.prepend(who);
        const screen = document.createElement("canvas");
        screen.width = 178;
        screen.height = 128;
        screen.dataset.robot = robot.number;
        screen.setAttribute("aria-label", `the LCD of robot ${robot.number}`);
        row.append(leds, screen);
        box.append(row);
        brick = { lights: lights, canvas: screen, frame: undefined, run: -1 };
        bricks.set(robot.number, brick);
      }
      for (const side of ["led0", "led1"]) {
        const color = ledColor(robot.leds, side);
        if (brick.lights[side].style.background !== color) brick.lights[side].style.background = color;
      }
      if (brick.frame !== robot.lcd_frame || brick.run !== state.run) showLcd(brick, robot, state.run);
    }
  }

  function showLcd(brick, robot, runNumber) {
    brick.frame = robot.lcd_frame;
    brick.run = runNumber;
    const c = brick.canvas.getContext("2d");
    if (robot.lcd_frame === null) {
      c.fillStyle = "rgb(155, 165, 140)";
      c.fillRect(0, 0, 178, 128);
      return;
    }
    const frame = robot.lcd_frame;
    window.PageToken.fetch(`api/lcd?robot=${robot.number}&frame=${frame}&run=${runNumber}`)
      .then((response) => (response.ok ? response.blob() : null))
      .then((blob) => (blob ? createImageBitmap(blob) : null))
      .then((image) => { if (image && brick.frame === frame) c.drawImage(image, 0, 0); })
      .catch(() => {});
  }

  // -- the robot's sensors: changed while paused (POST api/robot), saved to a robot file ----------
  async function loadRobot(number) {
    try {
      const response = await window.PageToken.fetch(`api/robot?robot=${number}`);
      const data = await response.json();
      if (!response.ok) return say(data.error, "error");
      robotEdit = data;
      showRobotEditor();
    } catch (err) {
      say(`Cannot read the robot: ${err}`, "error");
    }
  }

  function showRobotEditor() {
    const pick = document.getElementById("edit-robot");
    const count = latest ? latest.robots.length : 1;
    document.getElementById("edit-robot-box").hidden = count < 2;
    if (pick.options.length !== count) {
      pick.textContent = "";
      for (let n = 1; n <= count; n++) pick.append(new Option(`robot ${n}`, String(n)));
    }
    pick.value = String(robotEdit.robot);
    const t = document.getElementById("sensor-editor");
    t.textContent = "";
    const head = document.createElement("tr");
    for (const h of ["port", "kind", "angle°", "radius cm", "facing", ""]) {
      const th = document.createElement("th");
      th.textContent = h;
      head.append(th);
    }
    t.append(head);
    const sensors = robotEdit.mapping.sensors || [];
    sensors.forEach((sensor, i) => {
      const tr = document.createElement("tr");
      tr.dataset.index = i;
      const select = (field, options, value) => {
        const el = document.createElement("select");
        el.dataset.field = field;
        for (const o of options) el.append(new Option(o, o));
        el.value = value;
        el.addEventListener("change", () => {
          sensor[field] = field === "port" ? Number(el.value.slice(2)) : el.value;
          if (field === "kind") {
            const kind = robotEdit.kinds[el.value];
            for (const k of Object.keys(sensor)) {
              if (!["port", "kind", "angle_deg", "radius_cm", "facing", "aim_deg", "noise"].includes(k)) delete sensor[k];
            }
            if (!kind.facings.includes(sensor.facing)) sensor.facing = kind.facings[0];
            if (sensor.facing !== "forward") delete sensor.aim_deg;
            showRobotEditor();
          } else if (field === "facing" && el.value !== "forward") delete sensor.aim_deg;
        });
        return el;
      };
      const number = (field) => {
        const el = document.createElement("input");
        el.type = "number";
        el.step = field === "angle_deg" ? "5" : "0.5";
        el.dataset.field = field;
        el.value = String(sensor[field] ?? 0);
        el.addEventListener("change", () => { sensor[field] = Number(el.value); });
        return el;
      };
      const port = typeof sensor.port === "number" ? `in${sensor.port}` : String(sensor.port);
      const cells = [
        select("port", robotEdit.ports, port.startsWith("in") ? port : `in${port}`),
        select("kind", Object.keys(robotEdit.kinds), sensor.kind),
        number("angle_deg"),
        number("radius_cm"),
        select("facing", robotEdit.kinds[sensor.kind] ? robotEdit.kinds[sensor.kind].facings : ["down", "forward"], sensor.facing || "down"),
      ];
      const remove = document.createElement("button");
      remove.textContent = "×";
      remove.title = "take this sensor off";
      remove.addEventListener("click", () => { sensors.splice(i, 1); showRobotEditor(); });
      cells.push(remove);
      for (const el of cells) { const td = document.createElement("td"); td.append(el); tr.append(td); }
      t.append(tr);
    });
    const file = document.getElementById("robot-file-name");
    file.placeholder = robotEdit.file ? robotEdit.file.split("/").pop() : "new-file.yaml";
  }

  function addSensor() {
    if (!robotEdit) return;
    const sensors = robotEdit.mapping.sensors || (robotEdit.mapping.sensors = []);
    const used = new Set(sensors.map((s) => `in${String(s.port).replace("in", "")}`));
    const free = robotEdit.ports.find((p) => !used.has(p));
    if (!free) return say("All four sensor ports are taken.", "error");
    sensors.push({ port: Number(free.slice(2)), kind: "color", angle_deg: 0, radius_cm: 7, facing: "down" });
    showRobotEditor();
  }

  async function applyRobot() {
    if (!robotEdit) return;
    const answer = await post("api/robot", { robot: robotEdit.robot, mapping: robotEdit.mapping });
    if (answer) say(`Robot ${robotEdit.robot} changed; the run starts over at 0 s, paused.`, "ok");
  }

  async function saveRobot() {
    if (!robotEdit) return;
    const name = document.getElementById("robot-file-name").value.trim();
    const body = { robot: robotEdit.robot };
    if (name) body.file = name;
    let answer = await post("api/save-robot", body);
    if (!answer && name && document.getElementById("message").textContent.includes("replace: true")) {
      if (window.confirm(`${name} exists. Write over it (the old one is kept as ${name}.bak)?`)) {
        answer = await post("api/save-robot", { ...body, replace: true });
      }
    }
    if (answer) {
      say(`Saved robot ${answer.saved.robot} to ${answer.saved.saved}.`, "ok");
      loadRobot(robotEdit.robot);
    }
  }

  // -- the hand: robots and cells -----------------------------------------------------------------
  const dist = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);
  const round1 = (v) => Math.round(v * 10) / 10;

  function robotAt(p) {
    let hit = -1;
    const reach = Math.max(world.robot.front_cm, world.robot.width_cm / 2);
    poses().forEach((pose, i) => { if (dist(p, { x: pose.x_cm, y: pose.y_cm }) <= reach) hit = i; });
    return hit;
  }

  function robotCell(col, row) {
    return poses().some((pose) => Math.floor(pose.x_cm / world.cell_cm) === col && Math.floor(pose.y_cm / world.cell_cm) === row);
  }

  function onDown(event) {
    if (!world || !latest || !view || event.button !== 0) return;
    const p = W.eventCm(canvas, view, event);
    canvas.setPointerCapture(event.pointerId);
    const pose = poses()[selected];
    if (tool === "robot" && pose && dist(p, handlePoint(pose)) <= Math.max(3, (8 / view.scale) * view.dpr)) {
      gesture = { kind: "rotate", robot: selected, pose: { ...pose } };
      return;
    }
    const hit = robotAt(p);
    if (hit >= 0 && (tool === "robot" || !W.cellAt(world, p))) {
      selected = hit;
      const from = poses()[hit];
      gesture = { kind: "move", robot: hit, pose: { ...from }, offset: { x: p.x - from.x_cm, y: p.y - from.y_cm } };
      return;
    }
    if (tool === "robot") return;
    gesture = { kind: "cells", last: null, makeWall: undefined };
    applyAt(p);
  }

  function applyAt(p) {
    const c = W.cellAt(world, p);
    if (!c || c.join() === gesture.last) return;
    gesture.last = c.join();
    const [col, row] = c;
    const cell = world.cells[row][col];
    const border = col === 0 || row === 0 || col === world.width - 1 || row === world.height - 1;
    if (gesture.makeWall === undefined) gesture.makeWall = !cell.wall;
    if (tool === "wall" && gesture.makeWall && robotCell(col, row)) {
      return say("A robot is on this cell; move it before making the cell a wall.", "error");
    }
    const made = W.toolCell(tool, cell, {
      palette: world.palette, paintColor: document.getElementById("paint-color").value,
      makeWall: gesture.makeWall, border: border,
    });
    if (made.error) return say(made.error, "error");
    if (made.note) return say(made.note);
    const next = made.cell;
    if (next.wall === cell.wall && next.shade === cell.shade && next.color === cell.color) return;
    world.cells[row][col] = next; // drawn at once; the server's world follows
    worldLayerKey = "";
    post("api/cell", { col: col, row: row, wall: next.wall, shade: next.shade, color: next.color }).then((answer) => {
      if (!answer) loadWorld();
    });
  }

  function onMove(event) {
    if (!gesture || !view) return;
    const p = W.eventCm(canvas, view, event);
    if (gesture.kind === "cells") applyAt(p);
    else if (gesture.kind === "move") {
      gesture.pose.x_cm = round1(p.x - gesture.offset.x);
      gesture.pose.y_cm = round1(p.y - gesture.offset.y);
    } else if (gesture.kind === "rotate") {
      let deg = (Math.atan2(p.y - gesture.pose.y_cm, p.x - gesture.pose.x_cm) * 180) / Math.PI;
      gesture.pose.heading_deg = event.shiftKey ? Math.round(deg) : Math.round(deg / 15) * 15;
    }
  }

  async function onUp() {
    const done = gesture;
    gesture = null;
    if (!done || done.kind === "cells") return;
    const pose = done.pose;
    const answer = await post("api/move", {
      robot: done.robot + 1, x_cm: pose.x_cm, y_cm: pose.y_cm, heading_deg: pose.heading_deg,
    });
    if (answer) say(`Robot ${done.robot + 1} put at (${pose.x_cm}, ${pose.y_cm}) cm, heading ${pose.heading_deg}°.`, "ok");
  }

  function turn(step) {
    const pose = poses()[selected];
    if (!pose) return;
    post("api/move", { robot: selected + 1, x_cm: pose.x_cm, y_cm: pose.y_cm, heading_deg: pose.heading_deg + step });
  }

  function setTool(next) {
    tool = next;
    document.querySelectorAll("#tools button").forEach((b) => b.classList.toggle("active", b.dataset.tool === tool));
    const help = {
      robot: "Move robot: drag a robot; drag its orange handle (or Q / E) to turn it.",
      wall: "Wall / floor: click a cell to toggle it; drag to paint. The robot meets the new walls at once.",
      lighten: "Lighten: each click makes a grey floor cell a step lighter.",
      darken: "Darken: each click makes a grey floor cell a step darker.",
      paint: "Paint: click or drag over cells with the colour chosen beside the button.",
    };
    say(help[tool]);
  }

  // -- buttons and keys ---------------------------------------------------------------------------
  function togglePause() {
    if (!latest) return;
    post(latest.status === "running" ? "api/pause" : "api/resume");
  }

  async function saveWorld() {
    const answer = await post("api/save-world");
    if (answer) {
      const saved = answer.saved;
      say(saved.changed ? `Saved ${saved.saved} (the old version is in ${saved.saved}.bak).` : "Nothing changed; the file is as it was.", "ok");
    }
  }

  function onKey(event) {
    if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    const key = event.key.toLowerCase();
    if (key === " ") { event.preventDefault(); return togglePause(); }
    if (key === "s") return post("api/step", { ms: 100 });
    if (key === "r") return post("api/reload");
    if (key === "q" || key === "e") return turn((event.shiftKey ? 1 : 15) * (key === "q" ? 1 : -1));
    const tools = { m: "robot", w: "wall", l: "lighten", d: "darken", p: "paint" };
    if (tools[key]) setTool(tools[key]);
  }

  function init() {
    document.getElementById("pause").addEventListener("click", togglePause);
    document.getElementById("step").addEventListener("click", () => post("api/step", { ms: 100 }));
    document.getElementById("step-tick").addEventListener("click", () => post("api/step", { ticks: 1 }));
    document.getElementById("speed").addEventListener("change", (event) => {
      const v = event.target.value;
      post("api/speed", { speed: v === "max" ? null : Number(v) });
    });
    document.getElementById("reload").addEventListener("click", () => post("api/reload"));
    document.getElementById("reset").addEventListener("click", () => post("api/reset"));
    document.getElementById("save-world").addEventListener("click", saveWorld);
    document.getElementById("add-sensor").addEventListener("click", addSensor);
    document.getElementById("apply-robot").addEventListener("click", applyRobot);
    document.getElementById("save-robot").addEventListener("click", saveRobot);
    document.getElementById("edit-robot").addEventListener("change", (event) => loadRobot(Number(event.target.value)));
    document.querySelectorAll("#tools button").forEach((b) => b.addEventListener("click", () => setTool(b.dataset.tool)));
    document.getElementById("paint-color").addEventListener("change", () => setTool("paint"));
    canvas.addEventListener("pointerdown", onDown);
    canvas.addEventListener("pointermove", onMove);
    canvas.addEventListener("pointerup", onUp);
    canvas.addEventListener("pointercancel", onUp);
    document.addEventListener("keydown", onKey);
    setTool("robot");
    loadWorld().then(() => {
      listen();
      requestAnimationFrame(frame);
    });
  }

  // for tests and the curious: where things are on the page, in CSS pixels
  window.ev3live = {
    pageXY(xCm, yCm) {
      const box = canvas.getBoundingClientRect();
      return { x: box.left + W.pxX(view, xCm) / view.dpr, y: box.top + W.pxY(view, yCm) / view.dpr };
    },
    cellXY(col, row) {
      return this.pageXY((col + 0.5) * world.cell_cm, (row + 0.5) * world.cell_cm);
    },
    robotXY(index) {
      const pose = poses()[index || 0];
      return this.pageXY(pose.x_cm, pose.y_cm);
    },
    handleXY() {
      const h = handlePoint(poses()[selected]);
      return this.pageXY(h.x, h.y);
    },
    plotXY(fraction) {
      const box = plotCanvas.getBoundingClientRect();
      return { x: box.left + box.width * fraction, y: box.top + box.height / 2 };
    },
    state: () => latest,
    world: () => world,
    series: () => [...series.entries()].map(([key, s]) => ({ key: key, label: s.label, on: s.on, samples: s.samples.length })),
    frames: () => ({ count: frameStats.count, drawMs: frameStats.drawMs.slice() }),
    robotEdit: () => robotEdit,
    ready: () => world !== null && latest !== null && view !== null && latest.robots.length > 0,
  };
  init();
})();
