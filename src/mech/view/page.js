// mech view: draws one step of a sweep computed by mech.  It never solves: every number it
// shows is in the data (SI).  Plain script, no framework, no build step, no network.
(function () {
  "use strict";
  var D = JSON.parse(document.getElementById("mech-data").textContent);
  var NS = "http://www.w3.org/2000/svg";
  var N = D.param.si.length;
  var INK = "#1a1a1a", RED = "#c62828";
  var layers = { icentres: false, paths: false, centrodes: false, transmission: false };
  var current = D.own, playing = false, last = null, phase = D.own;

  // -- small helpers -------------------------------------------------------------------------
  function el(parent, tag, attrs, text) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) { if (attrs[k] !== null && attrs[k] !== undefined) e.setAttribute(k, attrs[k]); }
    if (text !== undefined) e.textContent = text;
    parent.appendChild(e);
    return e;
  }
  function clear(svg) { while (svg.firstChild) svg.removeChild(svg.firstChild); }
  function fmt(v, digits) {
    if (v === null || v === undefined || !isFinite(v)) return "—";
    if (v === 0) return "0";
    var a = Math.abs(v);
    if (a >= 1e-3 && a < 1e6) return String(Number(v.toPrecision(digits || 4)));
    var s = v.toExponential((digits || 4) - 1).split("e");
    var sup = { "-": "⁻", "0": "⁰", "1": "¹", "2": "²", "3": "³", "4": "⁴", "5": "⁵", "6": "⁶", "7": "⁷", "8": "⁸", "9": "⁹" };
    var exp = String(Number(s[1])).split("").map(function (c) { return sup[c] || c; }).join("");
    return Number(s[0]) + "×10" + exp;
  }
  function xy(i, k) { var p = D.xy[i][k]; return p && p[0] !== null ? p : null; }
  function hull(pts) {
    pts = pts.slice().sort(function (a, b) { return a[0] - b[0] || a[1] - b[1]; });
    if (pts.length < 3) return pts;
    function cross(o, a, b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }
    var lo = [], up = [], i;
    for (i = 0; i < pts.length; i++) { while (lo.length >= 2 && cross(lo[lo.length - 2], lo[lo.length - 1], pts[i]) <= 0) lo.pop(); lo.push(pts[i]); }
    for (i = pts.length - 1; i >= 0; i--) { while (up.length >= 2 && cross(up[up.length - 2], up[up.length - 1], pts[i]) <= 0) up.pop(); up.push(pts[i]); }
    return lo.slice(0, -1).concat(up.slice(0, -1));
  }
  function area(poly) {
    var s = 0;
    for (var i = 0; i < poly.length; i++) { var a = poly[i], b = poly[(i + 1) % poly.length]; s += a[0] * b[1] - b[0] * a[1]; }
    return Math.abs(s) / 2;
  }

  // -- the configuration's window: every step's points, fixed for the whole cycle --------------
  var box = (function () {
    var x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (var i = 0; i < N; i++) for (var k = 0; k < D.points.length; k++) {
      var p = xy(i, k); if (!p) continue;
      x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
    }
    if (!isFinite(x0)) { x0 = y0 = -1; x1 = y1 = 1; }
    var size = Math.max(x1 - x0, y1 - y0, 1e-12);
    var pad = 0.12 * size;
    return { x0: x0 - pad, y0: y0 - pad, x1: x1 + pad, y1: y1 + pad, size: size };
  })();
  var W = 560, H = 420;
  var k0 = Math.min(W / (box.x1 - box.x0), H / (box.y1 - box.y0));
  var ox = (W - k0 * (box.x1 - box.x0)) / 2, oy = (H - k0 * (box.y1 - box.y0)) / 2;
  function page(p) { return [ox + (p[0] - box.x0) * k0, oy + (box.y1 - p[1]) * k0]; }
  function pts(list) { return list.map(function (p) { var q = page(p); return q[0].toFixed(1) + "," + q[1].toFixed(1); }).join(" "); }

  function turnOf(i, guide) {
    if (guide === null) return 0;
    return D.angles[i][guide] - D.angles[D.own][guide];
  }

  function drawConfig(i) {
    var svg = document.getElementById("config");
    svg.setAttribute("viewBox", "0 0 " + W + " " + H);
    clear(svg);
    if (layers.paths) drawPaths(svg);
    if (layers.centrodes) drawCentrodes(svg, i);
    if (!D.ok[i]) {
      el(svg, "text", { x: W / 2, y: H / 2, "text-anchor": "middle", "class": "gap-note" }, "not assembled at this step");
      return;
    }
    D.sliders.forEach(function (s) { drawGuide(svg, i, s); });
    D.links.forEach(function (link) {
      var ps = link.points.map(function (k) { return xy(i, k); }).filter(Boolean);
      if (ps.length < 2) return;
      var h = hull(ps);
      if (h.length >= 3 && area(h) > 0.01 * Math.pow(box.size, 2) * 0.05) {
        el(svg, "polygon", { points: pts(h), fill: link.colour, "fill-opacity": 0.16, stroke: link.colour, "stroke-width": 2, "data-name": link.name, "class": "link" });
      } else {
        var best = [ps[0], ps[1]], d = -1;
        ps.forEach(function (a) { ps.forEach(function (b) { var e = Math.hypot(a[0] - b[0], a[1] - b[1]); if (e > d) { d = e; best = [a, b]; } }); });
        var a = page(best[0]), b = page(best[1]);
        el(svg, "line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: link.colour, "stroke-width": 4, "stroke-linecap": "round", "data-name": link.name, "class": "link" });
      }
    });
    D.pivots.forEach(function (k) {
      var p = xy(i, k); if (!p) return; var q = page(p);
      el(svg, "polygon", { points: [q[0], q[1], q[0] - 9, q[1] + 14, q[0] + 9, q[1] + 14].join(","), fill: "#fff", stroke: INK, "stroke-width": 1.2, "class": "ground-pivot" });
      el(svg, "line", { x1: q[0] - 14, y1: q[1] + 14, x2: q[0] + 14, y2: q[1] + 14, stroke: INK, "stroke-width": 1.2 });
      for (var t = -12; t <= 12; t += 5) el(svg, "line", { x1: q[0] + t, y1: q[1] + 14, x2: q[0] + t - 4, y2: q[1] + 19, stroke: INK, "stroke-width": 0.8 });
    });
    D.sliders.forEach(function (s) { drawSlider(svg, i, s); });
    D.pins.forEach(function (k) {
      var p = xy(i, k); if (!p) return; var q = page(p);
      el(svg, "circle", { cx: q[0], cy: q[1], r: 4, fill: "#fff", stroke: INK, "stroke-width": 1.3, "class": "pin", "data-name": D.points[k] });
    });
    D.named.forEach(function (k) {
      var p = xy(i, k); if (!p) return; var q = page(p);
      el(svg, "circle", { cx: q[0], cy: q[1], r: 3, fill: INK, "class": "point", "data-name": D.points[k] });
    });
    if (layers.transmission) drawTransmission(svg, i);
    drawLabels(svg, i);
    if (layers.icentres) drawICentres(svg, i);
  }

  function direction(i, s) {
    var t = turnOf(i, s.guide), c = Math.cos(t), n = Math.sin(t);
    return [c * s.dir[0] - n * s.dir[1], n * s.dir[0] + c * s.dir[1]];
  }
  function drawGuide(svg, i, s) {
    if (s.guide !== null || !s.block) return;
    var p = xy(i, s.point); if (!p) return;
    var u = direction(i, s), lo = Infinity, hi = -Infinity;
    for (var j = 0; j < N; j++) { var q = xy(j, s.point); if (!q) continue; var t = (q[0] - p[0]) * u[0] + (q[1] - p[1]) * u[1]; lo = Math.min(lo, t); hi = Math.max(hi, t); }
    var pad = 0.08 * box.size;
    var a = page([p[0] + (lo - pad) * u[0], p[1] + (lo - pad) * u[1]]), b = page([p[0] + (hi + pad) * u[0], p[1] + (hi + pad) * u[1]]);
    el(svg, "line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: "#777", "stroke-width": 0.8, "stroke-dasharray": "10 3 2 3", "class": "stroke-line" });
  }
  function drawSlider(svg, i, s) {
    var p = xy(i, s.point); if (!p) return;
    var u = direction(i, s), c = page(p), du = [u[0], -u[1]], nv = [-du[1], du[0]];
    if (s.block) {
      var a = 16, b = 10, corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(function (sg) {
        return (c[0] + du[0] * sg[0] * a + nv[0] * sg[1] * b).toFixed(1) + "," + (c[1] + du[1] * sg[0] * a + nv[1] * sg[1] * b).toFixed(1);
      });
      el(svg, "polygon", { points: corners.join(" "), fill: s.colour, "fill-opacity": 0.16, stroke: s.colour, "stroke-width": 1.6, "class": "slider", "data-name": s.joint });
    } else {
      [-1, 1].forEach(function (sg) {
        el(svg, "line", { x1: c[0] - du[0] * 24 + nv[0] * sg * 6, y1: c[1] - du[1] * 24 + nv[1] * sg * 6, x2: c[0] + du[0] * 24 + nv[0] * sg * 6, y2: c[1] + du[1] * 24 + nv[1] * sg * 6, stroke: s.colour, "stroke-width": 1.4, "class": "slot", "data-name": s.joint });
      });
    }
  }
  function drawLabels(svg, i) {
    var cx = 0, cy = 0, n = 0;
    D.points.forEach(function (_, k) { var p = xy(i, k); if (p) { var q = page(p); cx += q[0]; cy += q[1]; n++; } });
    cx /= Math.max(n, 1); cy /= Math.max(n, 1);
    D.points.forEach(function (name, k) {
      var p = xy(i, k); if (!p) return; var q = page(p);
      var dx = q[0] - cx, dy = q[1] - cy, d = Math.hypot(dx, dy) || 1;
      el(svg, "text", { x: q[0] + 14 * dx / d, y: q[1] + 14 * dy / d + 4, "text-anchor": "middle", "class": "label" }, D.labels[k]);
    });
  }
  function drawPaths(svg) {
    var fixed = {};
    D.pivots.forEach(function (k) { fixed[k] = true; });
    D.points.forEach(function (name, k) {
      if (fixed[k]) return;
      var runs = [[]];
      for (var i = 0; i < N; i++) { var p = xy(i, k); if (p) runs[runs.length - 1].push(p); else if (runs[runs.length - 1].length) runs.push([]); }
      runs.forEach(function (r) { if (r.length > 1) el(svg, "polyline", { points: pts(r), fill: "none", stroke: "#1f77b4", "stroke-width": 0.8, "class": "path", "data-name": name }); });
    });
  }
  function icAt(i, c) { var r = D.icentres.rows[i] && D.icentres.rows[i][c]; return r && r[2] !== null ? r : null; }
  function drawCentrodes(svg, i) {
    // the fixed centrode of each moving link is the locus of its I-centre with the frame (I1k);
    // the moving one is the same locus carried in the link, drawn where the link is now
    D.icentres.names.forEach(function (name, c) {
      var m = /^I1,?(\d+)$/.exec(name); if (!m) return;
      var li = Number(m[1]) - 2, link = D.moving[li]; if (link === undefined) return;
      if (D.pivots.some(function (k) { return D.links.some(function (l) { return l.name === link && l.points.indexOf(k) >= 0; }); })) return;
      var o = D.origins[li]; if (o === null) return;
      var fixed = [], moving = [], here = xy(i, o), th = D.angles[i][li];
      for (var j = 0; j < N; j++) {
        var r = icAt(j, c), p = xy(j, o); if (!r || r[2] !== 1 || !p || !here) continue;
        if (Math.abs(r[0] - box.x0) > 4 * box.size || Math.abs(r[1] - box.y0) > 4 * box.size) continue;
        fixed.push([r[0], r[1]]);
        var t = th - D.angles[j][li], c0 = Math.cos(t), s0 = Math.sin(t), dx = r[0] - p[0], dy = r[1] - p[1];
        moving.push([here[0] + c0 * dx - s0 * dy, here[1] + s0 * dx + c0 * dy]);
      }
      if (fixed.length > 1) el(svg, "polyline", { points: pts(fixed), fill: "none", stroke: "#2ca02c", "stroke-width": 1, "stroke-dasharray": "6 3", "class": "fixed-centrode", "data-name": link });
      if (moving.length > 1) el(svg, "polyline", { points: pts(moving), fill: "none", stroke: "#d62728", "stroke-width": 1, "stroke-dasharray": "2 2", "class": "moving-centrode", "data-name": link });
    });
  }
  function drawTransmission(svg, i) {
    var t = D.transmission; if (!t) return;
    var a = xy(i, t[0]), b = xy(i, t[1]), c = xy(i, t[2]); if (!a || !b || !c) return;
    var qa = page(a), qb = page(b), qc = page(c);
    var a1 = Math.atan2(qa[1] - qb[1], qa[0] - qb[0]), a2 = Math.atan2(qc[1] - qb[1], qc[0] - qb[0]);
    var d = a2 - a1; while (d > Math.PI) d -= 2 * Math.PI; while (d < -Math.PI) d += 2 * Math.PI;
    var r = 26, p1 = [qb[0] + r * Math.cos(a1), qb[1] + r * Math.sin(a1)], p2 = [qb[0] + r * Math.cos(a1 + d), qb[1] + r * Math.sin(a1 + d)];
    el(svg, "path", { d: "M" + p1.join(",") + " A" + r + "," + r + " 0 0 " + (d > 0 ? 1 : 0) + " " + p2.join(","), fill: "none", stroke: "#a0761a", "stroke-width": 1.5, "class": "transmission" });
    var mid = a1 + d / 2, mu = Math.abs(d) * 180 / Math.PI;
    el(svg, "text", { x: qb[0] + (r + 16) * Math.cos(mid), y: qb[1] + (r + 16) * Math.sin(mid), "text-anchor": "middle", fill: "#a0761a", "class": "label" }, "μ = " + mu.toFixed(1) + "°");
  }
  function drawICentres(svg, i) {
    var from = D.icentres.from === null ? null : xy(i, D.icentres.from);
    var far = [];
    D.icentres.names.forEach(function (name, c) {
      var r = icAt(i, c); if (!r) return;
      if (r[2] === 1) {
        var q = page(r);
        if (q[0] >= 6 && q[0] <= W - 6 && q[1] >= 6 && q[1] <= H - 6) {
          el(svg, "circle", { cx: q[0], cy: q[1], r: 4, fill: "none", stroke: RED, "stroke-width": 1, "class": "icentre", "data-name": name });
          el(svg, "text", { x: q[0] + 6, y: q[1] - 6, "class": "ic" }, name);
          return;
        }
        var dist = from ? Math.hypot(r[0] - from[0], r[1] - from[1]) : null;
        far.push([name, [q[0] - W / 2, q[1] - H / 2], dist === null ? "far" : fmt(dist / D.factor) + " " + D.unit + " from " + D.labels[D.icentres.from]]);
      } else {
        far.push([name, [r[0], -r[1]], "∞"]);
      }
    });
    far.forEach(function (f, n) {
      var u = f[1], m = Math.hypot(u[0], u[1]) || 1; u = [u[0] / m, u[1] / m];
      var t = Math.min(Math.abs((W / 2 - 16) / (u[0] || 1e-9)), Math.abs((H / 2 - 16) / (u[1] || 1e-9)));
      var tip = [W / 2 + u[0] * t, H / 2 + u[1] * t], tail = [tip[0] - u[0] * 26, tip[1] - u[1] * 26];
      el(svg, "line", { x1: tail[0], y1: tail[1], x2: tip[0], y2: tip[1], stroke: RED, "stroke-width": 1.2, "class": "icentre-arrow", "data-name": f[0] });
      var hx = tip[0] - u[0] * 7, hy = tip[1] - u[1] * 7;
      el(svg, "polygon", { points: [tip[0], tip[1], hx - u[1] * 3, hy + u[0] * 3, hx + u[1] * 3, hy - u[0] * 3].join(","), fill: RED });
      var anchor = tail[0] > W * 0.6 ? "end" : (tail[0] < W * 0.4 ? "start" : "middle");
      el(svg, "text", { x: tail[0], y: tail[1] + (u[1] > 0 ? -6 : 14) + 12 * (n % 2), "text-anchor": anchor, "class": "ic" }, f[0] + " → " + f[2]);
    });
  }

  // -- the polygons: one scale for the whole cycle, so lengths compare from step to step ---------
  function drawPolygon(P, i) {
    var svg = document.getElementById(P.kind);
    var S = 300, M = 34;
    svg.setAttribute("viewBox", "0 0 " + S + " " + S);
    clear(svg);
    if (!P.extent) {
      var m = 1e-300;
      P.values.forEach(function (row) { row.forEach(function (v) { if (v && v[0] !== null) m = Math.max(m, Math.abs(v[0]), Math.abs(v[1])); }); });
      P.extent = m;
    }
    var k = (S / 2 - M) / P.extent;
    function at(key) { var v = P.values[i][key]; return v && v[0] !== null ? [S / 2 + v[0] * k, S / 2 - v[1] * k] : null; }
    var row = P.values[i];
    if (!row || !D.ok[i]) return;
    P.vectors.forEach(function (v) {
      var a = at(v.s), b = at(v.e); if (!a || !b) return;
      var len = Math.hypot(b[0] - a[0], b[1] - a[1]); if (len < 0.5) return;
      var comp = !v.name;
      el(svg, "line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: v.colour, "stroke-width": comp ? 0.8 : 2, "stroke-dasharray": comp ? "4 3" : null, "class": comp ? "component" : "vector", "data-name": v.name || null });
      if (len > 9) {
        var u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len], h = comp ? 5 : 8, w = comp ? 2 : 3;
        var bx = b[0] - u[0] * h, by = b[1] - u[1] * h;
        el(svg, "polygon", { points: [b[0], b[1], bx - u[1] * w, by + u[0] * w, bx + u[1] * w, by - u[0] * w].join(","), fill: v.colour });
      }
    });
    var seen = {};
    P.labels.forEach(function (label, key) {
      if (!label) return; var q = at(key); if (!q) return;
      var spot = Math.round(q[0] / 3) + ":" + Math.round(q[1] / 3);
      if (seen[spot]) { seen[spot].textContent += ", " + label; return; }
      el(svg, "circle", { cx: q[0], cy: q[1], r: 2.2, fill: INK });
      var dx = q[0] - S / 2, dy = q[1] - S / 2, d = Math.hypot(dx, dy) || 1;
      if (d < 1) { dx = -1; dy = 1; d = Math.SQRT2; }
      seen[spot] = el(svg, "text", { x: q[0] + 11 * dx / d, y: q[1] + 11 * dy / d + 4, "text-anchor": "middle", "class": "image" }, label);
    });
    var bar = Math.pow(10, Math.floor(Math.log10(P.extent / 2))), barLen = bar * k;  // a round length
    el(svg, "line", { x1: 8, y1: S - 10, x2: 8 + barLen, y2: S - 10, stroke: INK, "stroke-width": 1.5, "class": "scalebar" });
    el(svg, "text", { x: 12 + barLen, y: S - 6, "font-size": 11, fill: "#555" }, fmt(bar) + " " + P.unit);
  }

  // -- the numbers ----------------------------------------------------------------------------
  var body = document.querySelector("#table tbody"), cells = [];
  (function () {
    var tr = document.createElement("tr");
    var th = document.createElement("td"); th.textContent = D.param.kind === "angle" ? D.param.drive + " angle" : D.param.drive + " position"; tr.appendChild(th);
    var td = document.createElement("td"); td.className = "num"; td.setAttribute("data-key", D.param.kind); tr.appendChild(td);
    body.appendChild(tr);
    cells.push([td, null]);
    D.table.forEach(function (row) {
      var r = document.createElement("tr");
      var a = document.createElement("td"); a.textContent = row.label; r.appendChild(a);
      var b = document.createElement("td"); b.className = "num"; b.setAttribute("data-key", row.key); r.appendChild(b);
      body.appendChild(r);
      cells.push([b, row]);
    });
  })();
  function showNumbers(i) {
    cells.forEach(function (c) {
      var td = c[0], row = c[1];
      if (row === null) {
        td.setAttribute("data-value", String(D.param.si[i]));
        td.textContent = D.param.kind === "angle" ? fmt(D.param.shown[i], 6) + "°" : fmt(D.param.shown[i], 6) + " " + D.param.unit;
        return;
      }
      var v = row.values[i];
      td.setAttribute("data-value", v === null ? "" : String(v));
      td.textContent = v === null ? "—" : fmt(v, 4) + " " + row.unit;
    });
  }

  // -- the slider and its marks ---------------------------------------------------------------
  var slider = document.getElementById("slider");
  slider.max = String(N - 1);
  function fraction(x) {
    var a = D.param.si[0], b = D.param.si[N - 1];
    if (D.param.kind === "angle") {  // the instants are N equal steps of a whole turn from the first
      var f = (((x - a) % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI);
      return Math.min(f / (2 * Math.PI) * N / Math.max(N - 1, 1), 1);
    }
    return Math.min(Math.max((x - a) / ((b - a) || 1), 0), 1);
  }
  (function () {
    var marks = document.getElementById("marks"), kinds = {};
    D.marks.forEach(function (m) {
      var d = document.createElement("div");
      d.className = "mark " + m.kind.replace(/ /g, "-");
      d.title = m.text;
      var f0 = fraction(m.at);
      d.style.left = (100 * f0) + "%";
      if (m.kind === "gap") { var f1 = fraction(m.to); d.style.width = (100 * Math.max(f1 - f0, 0.004)) + "%"; }
      marks.appendChild(d);
      kinds[m.kind] = (kinds[m.kind] || 0) + 1;
    });
    var words = Object.keys(kinds).map(function (k) { return kinds[k] + " " + k + (kinds[k] > 1 ? "s" : ""); });
    document.getElementById("marks-legend").textContent = words.length ? "Marked on the slider: " + words.join(", ") + " (hover a mark)." : "";
    document.getElementById("notes").textContent = D.notes.join(" ");
  })();

  function show(i) {
    current = Math.max(0, Math.min(N - 1, i));
    slider.value = String(current);
    drawConfig(current);
    D.polygons.forEach(function (P) { drawPolygon(P, current); });
    ["velocity", "acceleration"].forEach(function (k) {
      var has = D.polygons.some(function (P) { return P.kind === k; });
      document.getElementById(k + "-panel").style.display = has ? "" : "none";
    });
    showNumbers(current);
    var what = D.param.kind === "angle" ? D.param.drive + " at " + fmt(D.param.shown[current], 6) + "°" : D.param.drive + " at " + fmt(D.param.shown[current], 6) + " " + D.param.unit;
    document.getElementById("state").textContent = what + (D.ok[current] ? "" : " (not assembled)") + " — step " + (current + 1) + " of " + N;
  }

  // -- the address: #angle=<deg> or #position=<length> ----------------------------------------
  function fromHash() {
    var m = /^#(angle|position)=(-?[0-9.]+(?:e-?[0-9]+)?)$/i.exec(window.location.hash || "");
    if (!m || m[1].toLowerCase() !== D.param.kind) return D.own;
    var x = Number(m[2]);
    if (!isFinite(x)) return D.own;
    var best = D.own, d = Infinity;
    for (var i = 0; i < N; i++) {
      var e = D.param.kind === "angle" ? Math.abs((((D.param.shown[i] - x) % 360) + 540) % 360 - 180) : Math.abs(D.param.shown[i] - x);
      if (e < d - 1e-12) { d = e; best = i; }
    }
    return best;
  }

  slider.addEventListener("input", function () { stop(); show(Number(slider.value)); phase = current; });
  window.addEventListener("hashchange", function () { stop(); show(fromHash()); phase = current; });
  document.querySelectorAll("#layers input").forEach(function (box) {
    box.addEventListener("change", function () { layers[box.getAttribute("data-layer")] = box.checked; show(current); });
  });
  var button = document.getElementById("play");
  function stop() { playing = false; button.textContent = "▶ Play"; }
  button.addEventListener("click", function () {
    playing = !playing; button.textContent = playing ? "❚❚ Pause" : "▶ Play"; last = null; phase = current;
    if (playing) window.requestAnimationFrame(tick);
  });
  function tick(now) {
    if (!playing) return;
    if (last !== null) {
      var speed = Number(document.getElementById("speed").value);
      phase = (phase + (now - last) / 1000 * speed * N / 6) % N;  // 1×: the cycle in 6 s
      var i = Math.floor(phase);
      if (i !== current) show(i);
    }
    last = now;
    window.requestAnimationFrame(tick);
  }
  if (!D.transmission) document.querySelector('[data-layer="transmission"]').parentNode.style.display = "none";
  show(fromHash());
  phase = current;
  document.body.setAttribute("data-ready-ms", performance.now().toFixed(1));  // for load-time measurements
})();
