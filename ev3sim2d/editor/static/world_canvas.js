// The world on a canvas, shared by the editor's page (editor.js) and the live page (live/static/live.js):
// the drawing of cells and robots (as ev3sim2d/render/world_layer.py draws) and what a click of each cell
// tool does to a cell.  A `view` is {scale, left, top, dpr, heightCm}: pixels per cm and where the world's
// top-left corner is on the canvas.
"use strict";

window.WorldCanvas = (function () {
  const SURROUND = "rgb(40, 42, 48)";
  const WALL_EDGE = "rgb(120, 120, 126)";
  const BORDER_MESSAGE =
    "Border cells stay walls, so the robot cannot leave the world. You can change their colour with Paint colour.";

  const rgb = (c) => `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
  const wallCell = (color) => ({ wall: true, shade: null, color: color || null, char: null, region: null });
  const floorShade = (shade) => ({ wall: false, shade: shade, color: null, char: null, region: null });

  function displayRgb(cell, palette) {
    if (cell.color) return palette.colors[cell.color];
    const shade = cell.shade === null ? palette.wall_shade : cell.shade;
    const level = Math.max(0, Math.min(255, Math.round((shade * 255) / 100)));
    return [level, level, level];
  }

  // the view that fits a grid (width x height cells of cell_cm) into the canvas, with a margin
  function fit(canvas, grid) {
    const box = canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(box.width * dpr));
    const height = Math.max(1, Math.round(box.height * dpr));
    if (canvas.width !== width) canvas.width = width;
    if (canvas.height !== height) canvas.height = height;
    const margin = 12 * dpr;
    const w = grid.width * grid.cell_cm;
    const h = grid.height * grid.cell_cm;
    const scale = Math.max(0.01, Math.min((canvas.width - 2 * margin) / w, (canvas.height - 2 * margin) / h));
    return { scale: scale, left: (canvas.width - w * scale) / 2, top: (canvas.height - h * scale) / 2, dpr: dpr, heightCm: h };
  }
  const pxX = (view, x) => view.left + x * view.scale;
  const pxY = (view, y) => view.top + (view.heightCm - y) * view.scale;
  function eventCm(canvas, view, event) {
    const box = canvas.getBoundingClientRect();
    const px = (event.clientX - box.left) * view.dpr;
    const py = (event.clientY - box.top) * view.dpr;
    return { x: (px - view.left) / view.scale, y: view.heightCm - (py - view.top) / view.scale };
  }
  function cellAt(grid, p) {
    const col = Math.floor(p.x / grid.cell_cm);
    const row = Math.floor(p.y / grid.cell_cm);
    if (col < 0 || row < 0 || col >= grid.width || row >= grid.height) return null;
    return [col, row];
  }

  const hatches = new WeakMap();
  function hatchPattern(ctx) {
    if (hatches.has(ctx)) return hatches.get(ctx);
    const tile = document.createElement("canvas");
    tile.width = tile.height = 7;
    const t = tile.getContext("2d");
    t.fillStyle = "rgba(255, 255, 255, 0.11)";
    for (let i = 0; i < 7; i++) t.fillRect(i, 6 - i, 1, 1);
    const pattern = ctx.createPattern(tile, "repeat");
    hatches.set(ctx, pattern);
    return pattern;
  }

  // the surround, the cells, grid lines on floor, hatching and edges on walls
  function drawCells(ctx, view, grid, palette) {
    const canvas = ctx.canvas;
    const cm = grid.cell_cm;
    const s = cm * view.scale;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = SURROUND;
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    for (let row = 0; row < grid.height; row++) {
      for (let col = 0; col < grid.width; col++) {
        const x = pxX(view, col * cm);
        const y = pxY(view, (row + 1) * cm);
        ctx.fillStyle = rgb(displayRgb(grid.cells[row][col], palette));
        ctx.fillRect(Math.floor(x), Math.floor(y), Math.ceil(s) + 1, Math.ceil(s) + 1);
      }
    }
    ctx.fillStyle = "rgba(0, 0, 0, 0.10)";
    const line = Math.max(1, Math.round(view.dpr));
    for (let row = 0; row < grid.height; row++) {
      for (let col = 0; col < grid.width; col++) {
        const x = Math.floor(pxX(view, col * cm));
        const y = Math.floor(pxY(view, (row + 1) * cm));
        if (grid.cells[row][col].wall) {
          ctx.save();
          ctx.fillStyle = hatchPattern(ctx);
          ctx.fillRect(x, y, Math.ceil(s), Math.ceil(s));
          ctx.restore();
        } else if (s >= 6) {
          ctx.fillRect(x, y, Math.ceil(s), line);
          ctx.fillRect(x, y, line, Math.ceil(s));
        }
      }
    }
    ctx.strokeStyle = WALL_EDGE;
    ctx.lineWidth = line;
    ctx.beginPath();
    const wall = (c, r) => c >= 0 && r >= 0 && c < grid.width && r < grid.height && grid.cells[r][c].wall;
    for (let row = 0; row < grid.height; row++) {
      for (let col = 0; col < grid.width; col++) {
        if (!wall(col, row)) continue;
        const x0 = pxX(view, col * cm), x1 = pxX(view, (col + 1) * cm);
        const y0 = pxY(view, row * cm), y1 = pxY(view, (row + 1) * cm);
        if (!wall(col - 1, row)) { ctx.moveTo(x0, y0); ctx.lineTo(x0, y1); }
        if (!wall(col + 1, row)) { ctx.moveTo(x1, y0); ctx.lineTo(x1, y1); }
        if (!wall(col, row - 1)) { ctx.moveTo(x0, y0); ctx.lineTo(x1, y0); }
        if (!wall(col, row + 1)) { ctx.moveTo(x0, y1); ctx.lineTo(x1, y1); }
      }
    }
    ctx.stroke();
  }

  // a robot's body and heading arrow; body = {front_cm, back_cm, width_cm, color}
  function drawRobotBody(ctx, view, body, pose) {
    const a = (pose.heading_deg * Math.PI) / 180;
    ctx.save();
    ctx.translate(pxX(view, pose.x_cm), pxY(view, pose.y_cm));
    ctx.rotate(-a);
    const k = view.scale;
    ctx.fillStyle = `rgba(${body.color[0]}, ${body.color[1]}, ${body.color[2]}, 0.9)`;
    ctx.strokeStyle = "rgb(30, 30, 30)";
    ctx.lineWidth = Math.max(1, view.dpr * 1.5);
    const length = (body.front_cm + body.back_cm) * k;
    ctx.fillRect(-body.back_cm * k, -(body.width_cm / 2) * k, length, body.width_cm * k);
    ctx.strokeRect(-body.back_cm * k, -(body.width_cm / 2) * k, length, body.width_cm * k);
    ctx.fillStyle = "rgb(30, 30, 30)";
    ctx.beginPath();
    ctx.moveTo(body.front_cm * 0.9 * k, 0);
    ctx.lineTo(body.front_cm * 0.2 * k, -body.width_cm * 0.28 * k);
    ctx.lineTo(body.front_cm * 0.2 * k, body.width_cm * 0.28 * k);
    ctx.closePath();
    ctx.fill();
    ctx.restore();
  }

  // what a click of a cell tool makes of a cell: {cell} (maybe unchanged), or {error} / {note} to show.
  // tool: "wall" (makeWall says which way a gesture goes), "lighten", "darken", "paint" (paintColor or "plain")
  function toolCell(tool, cell, options) {
    const palette = options.palette;
    if (tool === "wall") {
      if (options.border) return { error: BORDER_MESSAGE };
      return { cell: options.makeWall ? wallCell(null) : floorShade(100) };
    }
    if (tool === "lighten" || tool === "darken") {
      if (cell.wall) return { error: "Walls have no shade; lighten and darken work on floor cells." };
      if (cell.color) return { error: "This cell is painted a colour; paint it plain (0) to give it a shade." };
      const steps = palette.shade_steps;
      const up = tool === "lighten";
      const next = up ? steps.find((v) => v > cell.shade) : [...steps].reverse().find((v) => v < cell.shade);
      if (next === undefined) return { note: up ? "This cell is already white." : "This cell is already black." };
      return { cell: floorShade(next) };
    }
    if (tool === "paint") {
      if (options.paintColor === "plain") return { cell: cell.wall ? wallCell(null) : floorShade(100) };
      return { cell: { wall: cell.wall, shade: null, color: options.paintColor, char: null, region: null } };
    }
    return { error: `unknown tool ${tool}` };
  }

  return {
    SURROUND, BORDER_MESSAGE, rgb, wallCell, floorShade, displayRgb, fit, pxX, pxY, eventCm, cellAt,
    drawCells, drawRobotBody, toolCell,
  };
})();
