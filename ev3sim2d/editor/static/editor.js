// The ev3sim2d world editor: draws the world as the renderer does and edits it by clicking.
// Plain JavaScript and a canvas; everything comes from the editor's own server (works offline).
"use strict";

(function () {
  const REGION = "rgb(0, 114, 178)";
  const HANDLE = "rgb(213, 94, 0)";
  const COLOR_KEYS = ["black", "blue", "green", "yellow", "red", "white", "brown"];
  const { wallCell, floorShade } = WorldCanvas;
  const HISTORY_LIMIT = 200;

  const canvas = document.getElementById("canvas");
  const ctx = canvas.getContext("2d");
  let world = null; // what the server sent: palette, robot, file
  let state = null; // {width, height, cell_cm, cells[row][col], starts, regions}
  let mode = "wall";
  let paintColor = "red";
  let selectedStart = 0;
  let selectedRegion = -1;
  let undoStack = [];
  let redoStack = [];
  let savedSnapshot = "";
  let pending = null; // snapshot taken when a gesture began
  let gesture = null;
  let view = { scale: 1, left: 0, top: 0, dpr: 1 };

  // -- messages ---------------------------------------------------------------------------------
  function say(text, kind) {
    const box = document.getElementById("message");
    box.textContent = text;
    box.className = kind || "";
  }

  // -- cells ------------------------------------------------------------------------------------
  const rgb = WorldCanvas.rgb;
  const isBorder = (col, row) => col === 0 || row === 0 || col === state.width - 1 || row === state.height - 1;
  const sameCell = (a, b) => a.wall === b.wall && a.shade === b.shade && a.color === b.color;

  function setCell(col, row, cell) {
    const old = state.cells[row][col];
    if (sameCell(old, cell)) return false;
    state.cells[row][col] = cell;
    return true;
  }

  function startCells() {
    return state.starts.map((p) => [Math.floor(p.x_cm / state.cell_cm), Math.floor(p.y_cm / state.cell_cm)]);
  }
  function isStartCell(col, row) {
    return startCells().some(([c, r]) => c === col && r === row);
  }

  // -- history ----------------------------------------------------------------------------------
  const snapshot = () => JSON.stringify(state);
  function begin() {
    pending = snapshot();
  }
  function commit() {
    if (pending === null) return;
    const now = snapshot();
    if (now !== pending) {
      undoStack.push(pending);
      if (undoStack.length > HISTORY_LIMIT) undoStack.shift();
      redoStack = [];
    }
    pending = null;
    refresh();
  }
  function change(fn) {
    begin();
    fn();
    commit();
  }
  function undo() {
    if (!undoStack.length) return say("Nothing to undo.");
    redoStack.push(snapshot());
    state = JSON.parse(undoStack.pop());
    fixSelection();
    say("Undone.");
    refresh();
  }
  function redo() {
    if (!redoStack.length) return say("Nothing to redo.");
    undoStack.push(snapshot());
    state = JSON.parse(redoStack.pop());
    fixSelection();
    say("Redone.");
    refresh();
  }
  function fixSelection() {
    if (selectedStart >= state.starts.length) selectedStart = 0;
    if (selectedRegion >= state.regions.length) selectedRegion = -1;
  }

  // -- view -------------------------------------------------------------------------------------
  function layout() {
    const box = canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(box.width * dpr));
    canvas.height = Math.max(1, Math.round(box.height * dpr));
    if (!state) return;
    const margin = 12 * dpr;
    const w = state.width * state.cell_cm;
    const h = state.height * state.cell_cm;
    const scale = Math.max(0.01, Math.min((canvas.width - 2 * margin) / w, (canvas.height - 2 * margin) / h));
    view = {
      scale: scale,
      left: (canvas.width - w * scale) / 2,
      top: (canvas.height - h * scale) / 2,
      dpr: dpr,
      heightCm: h,
    };
  }
  const pxX = (x) => view.left + x * view.scale;
  const pxY = (y) => view.top + (state.height * state.cell_cm - y) * view.scale;
  function eventCm(event) {
    const box = canvas.getBoundingClientRect();
    const px = (event.clientX - box.left) * view.dpr;
    const py = (event.clientY - box.top) * view.dpr;
    return { x: (px - view.left) / view.scale, y: state.height * state.cell_cm - (py - view.top) / view.scale };
  }
  function cellAt(p) {
    const col = Math.floor(p.x / state.cell_cm);
    const row = Math.floor(p.y / state.cell_cm);
    if (col < 0 || row < 0 || col >= state.width || row >= state.height) return null;
    return [col, row];
  }

  // -- drawing (world_canvas.js draws cells and robots, as ev3sim2d/render/world_layer.py does) --------
  function draw() {
    if (!state) return;
    layout();
    WorldCanvas.drawCells(ctx, view, state, world.palette);
    drawLegendRegions();
    state.regions.forEach((region, i) => drawRegion(region, i === selectedRegion && mode === "regions"));
    if (gesture && gesture.kind === "region") drawRegion({ name: "", rects: [gesture.rect] }, true);
    state.starts.forEach((pose, i) => drawRobot(pose, i));
  }

  function dashed(width) {
    ctx.strokeStyle = REGION;
    ctx.lineWidth = width;
    const dash = Math.max(4, view.scale * 2);
    ctx.setLineDash([dash, dash]);
  }

  function label(text, x, y) {
    const size = Math.max(10, Math.round(12 * view.dpr));
    ctx.font = `bold ${size}px ui-monospace, monospace`;
    const w = ctx.measureText(text).width;
    ctx.fillStyle = "white";
    ctx.fillRect(x, y, w + 4, size + 3);
    ctx.fillStyle = REGION;
    ctx.textBaseline = "top";
    ctx.fillText(text, x + 2, y + 2);
  }

  function drawRegion(region, selected) {
    const thick = Math.max(1, Math.round(view.scale * 0.35));
    for (const [x0, y0, x1, y1] of region.rects) {
      const px0 = pxX(x0), py0 = pxY(y1), w = (x1 - x0) * view.scale, h = (y1 - y0) * view.scale;
      if (selected) {
        ctx.fillStyle = "rgba(0, 114, 178, 0.25)";
        ctx.fillRect(px0, py0, w, h);
      }
      dashed(thick);
      ctx.strokeRect(px0, py0, w, h);
    }
    ctx.setLineDash([]);
    if (region.name && region.rects.length) {
      const left = Math.min(...region.rects.map((r) => r[0]));
      const top = Math.max(...region.rects.map((r) => r[3]));
      label(region.name, pxX(left) + thick + 1, pxY(top) + thick + 1);
    }
  }

  function drawLegendRegions() {
    const names = new Map();
    for (let row = state.height - 1; row >= 0; row--) {
      for (let col = 0; col < state.width; col++) {
        const name = state.cells[row][col].region;
        if (name && !names.has(name)) names.set(name, [col, row]);
      }
    }
    if (!names.size) return;
    const thick = Math.max(1, Math.round(view.scale * 0.35));
    const regionOf = (c, r) =>
      c >= 0 && r >= 0 && c < state.width && r < state.height ? state.cells[r][c].region : null;
    dashed(thick);
    ctx.beginPath();
    for (let row = 0; row < state.height; row++) {
      for (let col = 0; col < state.width; col++) {
        const name = state.cells[row][col].region;
        if (!name) continue;
        const x0 = pxX(col * state.cell_cm), x1 = pxX((col + 1) * state.cell_cm);
        const y0 = pxY(row * state.cell_cm), y1 = pxY((row + 1) * state.cell_cm);
        if (regionOf(col - 1, row) !== name) { ctx.moveTo(x0, y0); ctx.lineTo(x0, y1); }
        if (regionOf(col + 1, row) !== name) { ctx.moveTo(x1, y0); ctx.lineTo(x1, y1); }
        if (regionOf(col, row - 1) !== name) { ctx.moveTo(x0, y0); ctx.lineTo(x1, y0); }
        if (regionOf(col, row + 1) !== name) { ctx.moveTo(x0, y1); ctx.lineTo(x1, y1); }
      }
    }
    ctx.stroke();
    ctx.setLineDash([]);
    for (const [name, [col, row]] of names) {
      label(name, pxX(col * state.cell_cm) + thick + 1, pxY((row + 1) * state.cell_cm) + thick + 1);
    }
  }

  function handlePoint(pose) {
    const reach = world.robot.front_cm + 6;
    const a = (pose.heading_deg * Math.PI) / 180;
    return { x: pose.x_cm + reach * Math.cos(a), y: pose.y_cm + reach * Math.sin(a) };
  }

  function drawRobot(pose, index) {
    const cx = pxX(pose.x_cm), cy = pxY(pose.y_cm);
    const k = view.scale;
    WorldCanvas.drawRobotBody(ctx, view, world.robot, pose);
    if (state.starts.length > 1) label(String(index + 1), cx - 6, cy - 6);
    if (mode === "robot" && index === selectedStart) {
      const h = handlePoint(pose);
      ctx.strokeStyle = HANDLE;
      ctx.lineWidth = Math.max(1, view.dpr * 1.5);
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      ctx.lineTo(pxX(h.x), pxY(h.y));
      ctx.stroke();
      ctx.fillStyle = HANDLE;
      ctx.beginPath();
      ctx.arc(pxX(h.x), pxY(h.y), Math.max(5 * view.dpr, 1.6 * k), 0, 2 * Math.PI);
      ctx.fill();
    }
  }

  // -- the side panel -----------------------------------------------------------------------------
  function refresh() {
    document.querySelectorAll("#modes button").forEach((b) => b.classList.toggle("active", b.dataset.mode === mode));
    document.querySelectorAll("#palette button").forEach((b) => b.classList.toggle("active", b.dataset.color === paintColor));
    document.getElementById("undo").disabled = !undoStack.length;
    document.getElementById("redo").disabled = !redoStack.length;
    const dirty = snapshot() !== savedSnapshot;
    document.getElementById("save").classList.toggle("dirty", dirty);
    document.getElementById("save").textContent = dirty ? "Save *" : "Save";
    document.getElementById("grid-width").value = state.width;
    document.getElementById("grid-height").value = state.height;
    document.getElementById("cell-cm").value = state.cell_cm;
    const pose = state.starts[selectedStart];
    document.getElementById("status").textContent =
      `${state.width} × ${state.height} cells of ${state.cell_cm} cm · robot ${selectedStart + 1} at ` +
      `(${pose.x_cm}, ${pose.y_cm}) cm, heading ${pose.heading_deg}°`;
    refreshRegions();
    draw();
  }

  function refreshRegions() {
    const list = document.getElementById("regions");
    list.textContent = "";
    state.regions.forEach((region, i) => {
      const item = document.createElement("li");
      item.className = i === selectedRegion ? "selected" : "";
      const input = document.createElement("input");
      input.type = "text";
      input.value = region.name;
      input.setAttribute("aria-label", "region name");
      input.addEventListener("focus", () => { selectedRegion = i; draw(); });
      input.addEventListener("change", () => renameRegion(i, input.value.trim()));
      const remove = document.createElement("button");
      remove.textContent = "Delete";
      remove.addEventListener("click", () => deleteRegion(i));
      item.append(input, remove);
      list.append(item);
    });
    const legendNames = new Set();
    state.cells.forEach((row) => row.forEach((c) => c.region && legendNames.add(c.region)));
    for (const name of legendNames) {
      const item = document.createElement("li");
      const span = document.createElement("span");
      span.className = "legend-region";
      span.textContent = `${name} (legend cells)`;
      span.title = "made by a legend character: follows its cells";
      item.append(span);
      list.append(item);
    }
  }

  function renameRegion(i, name) {
    if (!name) return (say("A region needs a name.", "error"), refresh());
    if (state.regions.some((r, j) => j !== i && r.name === name)) {
      return (say(`There is already a region called ${name}.`, "error"), refresh());
    }
    change(() => { state.regions[i].name = name; });
    say(`Region renamed to ${name}.`);
  }

  function deleteRegion(i) {
    const name = state.regions[i].name;
    change(() => { state.regions.splice(i, 1); });
    selectedRegion = -1;
    say(`Region ${name} deleted.`);
    refresh();
  }

  function setMode(next) {
    mode = next;
    const help = {
      wall: "Wall / floor: click a cell to toggle it; drag to paint.",
      lighten: "Lighten: each click makes a grey floor cell a step lighter.",
      darken: "Darken: each click makes a grey floor cell a step darker.",
      paint: `Paint colour (${paintColor}): click or drag over cells; walls keep blocking.`,
      robot: "Robot start: drag the robot; drag the orange handle (or Q / E) to turn it.",
      regions: "Regions: drag over cells to draw one; click one to select; Delete removes it.",
    };
    say(help[mode]);
    refresh();
  }

  // -- editing cells --------------------------------------------------------------------------
  function applyCell(col, row, first) {
    const cell = state.cells[row][col];
    if (mode === "wall" && !isBorder(col, row)) {
      if (first) gesture.makeWall = !cell.wall;
      if (gesture.makeWall && isStartCell(col, row)) {
        return say("The robot starts on this cell; move the robot before making it a wall.", "error");
      }
    }
    const made = WorldCanvas.toolCell(mode, cell, {
      palette: world.palette, paintColor: paintColor, makeWall: gesture.makeWall, border: isBorder(col, row),
    });
    if (made.error) return say(made.error, "error");
    if (made.note) return say(made.note);
    setCell(col, row, made.cell);
  }

  function snapPose(p, free) {
    const s = state.cell_cm;
    if (free) return { x: Math.round(p.x * 10) / 10, y: Math.round(p.y * 10) / 10 };
    return { x: (Math.floor(p.x / s) + 0.5) * s, y: (Math.floor(p.y / s) + 0.5) * s };
  }
  function onFloor(x, y) {
    const c = cellAt({ x: x, y: y });
    return c !== null && !state.cells[c[1]][c[0]].wall;
  }
  const round1 = (v) => Math.round(v * 10) / 10;
  function normHeading(deg) {
    let h = round1(deg) % 360;
    if (h > 180) h -= 360;
    if (h <= -180) h += 360;
    return h === 0 ? 0 : h;
  }

  function onDown(event) {
    if (!state || event.button !== 0) return;
    const p = eventCm(event);
    canvas.setPointerCapture(event.pointerId);
    begin();
    if (mode === "robot") {
      const dist = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);
      let hit = -1;
      state.starts.forEach((pose, i) => {
        if (dist(p, { x: pose.x_cm, y: pose.y_cm }) <= Math.max(world.robot.front_cm, world.robot.width_cm / 2)) hit = i;
      });
      const pose = state.starts[selectedStart];
      const handle = handlePoint(pose);
      if (dist(p, handle) <= Math.max(3, 8 / view.scale * view.dpr)) {
        gesture = { kind: "rotate" };
      } else {
        if (hit >= 0) selectedStart = hit;
        gesture = { kind: "move", from: { x: state.starts[selectedStart].x_cm, y: state.starts[selectedStart].y_cm } };
        moveRobot(p, event.shiftKey);
      }
    } else if (mode === "regions") {
      const c = cellAt(p);
      const inside = state.regions.findIndex((r) => r.rects.some(([x0, y0, x1, y1]) => x0 <= p.x && p.x < x1 && y0 <= p.y && p.y < y1));
      if (c === null) { gesture = null; return; }
      gesture = { kind: "region", from: c, rect: cellRect(c, c), clicked: inside };
    } else {
      const c = cellAt(p);
      gesture = { kind: "cells", last: null };
      if (c) { gesture.last = c.join(); applyCell(c[0], c[1], true); }
    }
    draw();
  }

  function cellRect(a, b) {
    const s = state.cell_cm;
    return [Math.min(a[0], b[0]) * s, Math.min(a[1], b[1]) * s, (Math.max(a[0], b[0]) + 1) * s, (Math.max(a[1], b[1]) + 1) * s];
  }

  function moveRobot(p, free) {
    const q = snapPose(p, free);
    if (!onFloor(q.x, q.y)) return;
    state.starts[selectedStart].x_cm = round1(q.x);
    state.starts[selectedStart].y_cm = round1(q.y);
  }

  function onMove(event) {
    if (!gesture) return;
    const p = eventCm(event);
    if (gesture.kind === "cells") {
      const c = cellAt(p);
      if (c && c.join() !== gesture.last) {
        gesture.last = c.join();
        if (gesture.makeWall === undefined && mode === "wall") applyCell(c[0], c[1], true);
        else applyCell(c[0], c[1], false);
      }
    } else if (gesture.kind === "move") {
      moveRobot(p, event.shiftKey);
    } else if (gesture.kind === "rotate") {
      const pose = state.starts[selectedStart];
      let deg = (Math.atan2(p.y - pose.y_cm, p.x - pose.x_cm) * 180) / Math.PI;
      deg = event.shiftKey ? Math.round(deg) : Math.round(deg / 15) * 15;
      pose.heading_deg = normHeading(deg);
    } else if (gesture.kind === "region") {
      const c = cellAt(p);
      if (c) { gesture.rect = cellRect(gesture.from, c); gesture.moved = gesture.moved || c.join() !== gesture.from.join(); }
    }
    refreshLight();
  }

  function refreshLight() {
    draw();
    const pose = state.starts[selectedStart];
    document.getElementById("status").textContent =
      `${state.width} × ${state.height} cells of ${state.cell_cm} cm · robot ${selectedStart + 1} at ` +
      `(${pose.x_cm}, ${pose.y_cm}) cm, heading ${pose.heading_deg}°`;
  }

  function onUp() {
    if (!gesture) return;
    if (gesture.kind === "region") {
      if (!gesture.moved && gesture.clicked >= 0) {
        selectedRegion = gesture.clicked;
        say(`Region ${state.regions[selectedRegion].name} selected: rename it in the list, or press Delete.`);
      } else {
        let n = state.regions.length + 1;
        while (state.regions.some((r) => r.name === `region${n}`)) n++;
        state.regions.push({ name: `region${n}`, rects: [gesture.rect] });
        selectedRegion = state.regions.length - 1;
        say(`Region region${n} drawn; give it a name in the list.`);
      }
    } else if (gesture.kind === "rotate" || gesture.kind === "move") {
      const pose = state.starts[selectedStart];
      say(`Robot ${selectedStart + 1} starts at (${pose.x_cm}, ${pose.y_cm}) cm, heading ${pose.heading_deg}°.`);
    }
    gesture = null;
    commit();
  }

  // -- grid size and cell size ----------------------------------------------------------------------
  function resize(width, height) {
    if (!(width >= 3 && width <= 200 && height >= 3 && height <= 200)) {
      return say("A world is 3 to 200 cells each way.", "error");
    }
    change(() => {
      const old = state.cells, ow = state.width, oh = state.height;
      const cells = [];
      for (let row = 0; row < height; row++) {
        const line = [];
        for (let col = 0; col < width; col++) {
          const border = col === 0 || row === 0 || col === width - 1 || row === height - 1;
          if (border) {
            const oc = col === width - 1 ? ow - 1 : Math.min(col, ow - 1);
            const orow = row === height - 1 ? oh - 1 : Math.min(row, oh - 1);
            const c = old[orow][oc];
            line.push(c.wall ? c : wallCell(null));
          } else if (col < ow - 1 && row < oh - 1) {
            line.push(old[row][col]);
          } else {
            line.push(floorShade(100));
          }
        }
        cells.push(line);
      }
      state.cells = cells;
      state.width = width;
      state.height = height;
      const s = state.cell_cm, wcm = width * s, hcm = height * s;
      state.regions = state.regions
        .map((r) => ({ name: r.name, rects: r.rects.map(([x0, y0, x1, y1]) => [x0, y0, Math.min(x1, wcm - s), Math.min(y1, hcm - s)]).filter(([x0, y0, x1, y1]) => x0 < x1 && y0 < y1) }))
        .filter((r) => r.rects.length);
      for (const pose of state.starts) {
        if (!onFloor(pose.x_cm, pose.y_cm)) {
          pose.x_cm = round1((Math.floor(width / 2) + 0.5) * s);
          pose.y_cm = round1((Math.floor(height / 2) + 0.5) * s);
        }
      }
    });
    say(`The grid is now ${width} × ${height} cells.`);
  }

  function setCellCm(value) {
    if (!(value >= 1 && value <= 1000)) return say("The cell size is from 1 to 1000 cm.", "error");
    const k = value / state.cell_cm;
    change(() => {
      state.cell_cm = value;
      for (const pose of state.starts) { pose.x_cm = round1(pose.x_cm * k); pose.y_cm = round1(pose.y_cm * k); }
      state.regions.forEach((r) => { r.rects = r.rects.map((rect) => rect.map((v) => Math.round(v * k * 1000) / 1000)); });
    });
    say(`Cells are now ${value} cm; the robot and the regions moved with them.`);
  }

  // -- saving -----------------------------------------------------------------------------------
  function payload() {
    return {
      cell_cm: state.cell_cm,
      cells: state.cells.map((row) => row.map((c) => ({ wall: c.wall, shade: c.shade, color: c.color, char: c.char }))),
      starts: state.starts.map((p) => ({ x_cm: p.x_cm, y_cm: p.y_cm, heading_deg: p.heading_deg })),
      regions: state.regions.map((r) => ({ name: r.name, rects: r.rects })),
    };
  }

  async function save() {
    say("Saving…");
    try {
      const response = await window.PageToken.fetch("api/save", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify(payload()),
      });
      const answer = await response.json();
      if (!response.ok) return say(`Not saved: ${answer.error}`, "error");
      load(answer.world, false);
      say(answer.changed ? `Saved ${answer.saved} (the old version is in ${answer.saved}.bak).` : "Nothing changed; the file is as it was.", "ok");
    } catch (err) {
      say(`Not saved: the editor's server did not answer (${err}). Is ev3sim2d edit still running?`, "error");
    }
  }

  function fromWorld(data) {
    return {
      width: data.width,
      height: data.height,
      cell_cm: data.cell_cm,
      cells: data.cells,
      starts: data.starts,
      regions: data.regions,
    };
  }

  function load(data, fresh) {
    world = data;
    state = fromWorld(data);
    savedSnapshot = snapshot();
    if (fresh) { undoStack = []; redoStack = []; }
    fixSelection();
    document.getElementById("title").textContent = data.title;
    document.getElementById("file").textContent = data.file;
    document.title = `${data.title} – ev3sim2d editor`;
    refresh();
  }

  // -- keys -------------------------------------------------------------------------------------
  function onKey(event) {
    if (!state) return;
    const typing = event.target instanceof HTMLInputElement;
    const key = event.key.toLowerCase();
    if ((event.ctrlKey || event.metaKey) && !event.altKey) {
      if (key === "z" && !event.shiftKey) { event.preventDefault(); return undo(); }
      if (key === "y" || (key === "z" && event.shiftKey)) { event.preventDefault(); return redo(); }
      if (key === "s") { event.preventDefault(); return save(); }
      return;
    }
    if (typing || event.altKey) return;
    const modes = { w: "wall", l: "lighten", d: "darken", p: "paint", r: "robot", g: "regions" };
    if (modes[key]) return setMode(modes[key]);
    if (/^[0-7]$/.test(event.key)) {
      paintColor = event.key === "0" ? "plain" : COLOR_KEYS[Number(event.key) - 1];
      return setMode("paint");
    }
    if ((key === "delete" || key === "backspace") && mode === "regions" && selectedRegion >= 0) {
      event.preventDefault();
      return deleteRegion(selectedRegion);
    }
    if (key === "q" || key === "e") {
      const step = (event.shiftKey ? 1 : 15) * (key === "q" ? 1 : -1);
      const pose = state.starts[selectedStart];
      change(() => { pose.heading_deg = normHeading(pose.heading_deg + step); });
      return say(`Robot ${selectedStart + 1} heading ${pose.heading_deg}°.`);
    }
    const arrows = { arrowleft: [-1, 0], arrowright: [1, 0], arrowup: [0, 1], arrowdown: [0, -1] };
    if (arrows[key] && mode === "robot") {
      event.preventDefault();
      const pose = state.starts[selectedStart];
      const x = pose.x_cm + arrows[key][0] * state.cell_cm, y = pose.y_cm + arrows[key][1] * state.cell_cm;
      if (!onFloor(x, y)) return say("The robot starts on floor; that cell is a wall.", "error");
      change(() => { pose.x_cm = round1(x); pose.y_cm = round1(y); });
    }
  }

  // -- start --------------------------------------------------------------------------------------
  function buildPalette() {
    const box = document.getElementById("palette");
    COLOR_KEYS.concat(["plain"]).forEach((name, i) => {
      const b = document.createElement("button");
      b.dataset.color = name;
      const key = name === "plain" ? 0 : i + 1;
      b.textContent = `${key} ${name}`;
      const c = name === "plain" ? [255, 255, 255] : world.palette.colors[name];
      b.style.background = rgb(c);
      if (c[0] * 0.3 + c[1] * 0.6 + c[2] * 0.1 > 150) b.classList.add("light");
      b.addEventListener("click", () => { paintColor = name; setMode("paint"); });
      box.append(b);
    });
  }

  async function init() {
    document.querySelectorAll("#modes button").forEach((b) => b.addEventListener("click", () => setMode(b.dataset.mode)));
    document.getElementById("undo").addEventListener("click", undo);
    document.getElementById("redo").addEventListener("click", redo);
    document.getElementById("save").addEventListener("click", save);
    document.getElementById("resize").addEventListener("click", () =>
      resize(Number(document.getElementById("grid-width").value), Number(document.getElementById("grid-height").value)));
    document.getElementById("set-cell-cm").addEventListener("click", () =>
      setCellCm(Number(document.getElementById("cell-cm").value)));
    canvas.addEventListener("pointerdown", onDown);
    canvas.addEventListener("pointermove", onMove);
    canvas.addEventListener("pointerup", onUp);
    canvas.addEventListener("pointercancel", onUp);
    document.addEventListener("keydown", onKey);
    window.addEventListener("resize", draw);
    window.addEventListener("beforeunload", (event) => {
      if (state && snapshot() !== savedSnapshot) { event.preventDefault(); event.returnValue = ""; }
    });
    try {
      const response = await window.PageToken.fetch("api/world");
      const data = await response.json();
      if (!response.ok) return say(`Cannot load the world: ${data.error}`, "error");
      load(data, true);
      buildPalette();
      setMode("wall");
    } catch (err) {
      say(`Cannot load the world: ${err}`, "error");
    }
  }

  // for tests and the curious: where a cell or a point (cm) is on the page, in CSS pixels
  window.ev3edit = {
    pageXY(xCm, yCm) {
      const box = canvas.getBoundingClientRect();
      return { x: box.left + pxX(xCm) / view.dpr, y: box.top + pxY(yCm) / view.dpr };
    },
    cellXY(col, row) {
      return this.pageXY((col + 0.5) * state.cell_cm, (row + 0.5) * state.cell_cm);
    },
    handleXY() {
      const h = handlePoint(state.starts[selectedStart]);
      return this.pageXY(h.x, h.y);
    },
    state: () => JSON.parse(snapshot()),
    ready: () => state !== null,
  };
  init();
})();
