// Draws the report's charts from the JSON block with uPlot; the tables are already in the page.
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("report-data").textContent);
  var origin = data.origin, timed = data.timed;
  var COLORS = { exception: "#d62728", protection: "#9467bd", crc: "#ff7f0e", noise: "#8c564b",
                 silence: "#17becf", unanswered: "#7f7f7f" };

  function width(el) { return Math.max(320, Math.min(1100, (el.clientWidth || 900) - 10)); }
  // x values as drawn: the capture's seconds from its first item for -t r/d/dd (ticks at round
  // relative times), epoch seconds for the clocks (a, ad, u, ud) and e, frame numbers when untimed.
  var shift = 0;
  function xs(list) { return list.map(function (x) { return x + origin - shift; }); }
  function at(x) { return x + origin - shift; }
  // Every chart spans the whole capture, so that moments line up from chart to chart, with the same
  // axis width on the left; times read as the time column (-t): relative seconds (r, d, dd), epoch
  // seconds (e), local (a, ad) or UTC (u, ud) clock.
  var x0 = origin, x1 = origin + data.span;
  if (x1 <= x0) { x1 = x0 + 1; }
  var clock = data.clock || "r", first = data.first != null ? data.first : origin;
  var wall = timed && (clock.charAt(0) === "a" || clock.charAt(0) === "u");
  if (timed && !wall && clock !== "e") { shift = first; }
  x0 -= shift; x1 -= shift;
  var YSIZE = 190;  // every y axis as wide as the widest (enumeration labels): x positions line up
  function xScale() { return { time: wall, range: function () { return [x0, x1]; } }; }
  function seconds(v) {
    var text = v.toFixed(3);
    return text.indexOf(".") < 0 ? text : text.replace(/\.?0+$/, "");
  }
  function xAxis() {
    // (several files read as one bus: their frames numbered on from file to file, data.inputs)
    if (!timed) { return { label: data.inputs ? "frame, numbered on from file to file" : "frame" }; }
    if (wall) { return {}; }
    return { label: clock === "e" ? "epoch s" : "s", values: function (u, splits) { return splits.map(seconds); } };
  }
  function yAxis(extra) {
    // A label space on every axis, labelled or not, so that every plot starts at the same x.
    var axis = { size: YSIZE, labelSize: 24, label: "\u00a0" };
    for (var k in extra) { axis[k] = extra[k]; }
    return axis;
  }
  function chartOptions(opts) {
    if (wall && clock.charAt(0) === "u") { opts.tzDate = function (ts) { return uPlot.tzDate(new Date(ts * 1e3), "Etc/UTC"); }; }
    return opts;
  }
  var written = {};
  (data.written || []).forEach(function (key) { written[key] = true; });

  function shortLabels(labels) {
    // Enumeration texts cut to 26 characters unless that makes two of them read the same: then the
    // prefix they share is dropped (status words differ at their end: "Ready to switch on, ...").
    var keys = Object.keys(labels), texts = keys.map(function (k) { return labels[k]; });
    function cut(t) { return t.length > 26 ? t.slice(0, 25) + "…" : t; }
    var cuts = texts.map(cut), seen = {}, clash = false;
    cuts.forEach(function (t) { if (seen[t]) { clash = true; } seen[t] = true; });
    var out = {};
    if (!clash || texts.length < 2) { keys.forEach(function (k, i) { out[k] = cuts[i]; }); return out; }
    var prefix = texts.reduce(function (a, b) { var n = 0; while (n < a.length && a.charAt(n) === b.charAt(n)) { n++; } return a.slice(0, n); });
    var stop = Math.max(prefix.lastIndexOf(", "), prefix.lastIndexOf(" "));
    var drop = stop > 0 ? stop + 1 : prefix.length;
    keys.forEach(function (k, i) { var rest = texts[i].slice(drop).replace(/^\s+/, ""); out[k] = k + ": …" + cut(rest); });
    return out;
  }

  function bandsPlugin(bands) {
    // Outages: the span from the first to the last unanswered request, shaded, edges drawn.
    return { hooks: { draw: function (u) {
      var ctx = u.ctx, top = u.bbox.top, height = u.bbox.height;
      ctx.save();
      bands.forEach(function (band) {
        var a = u.valToPos(at(band.x0), "x", true), b = u.valToPos(at(band.x1), "x", true);
        ctx.fillStyle = "rgba(127,127,127,0.25)"; ctx.fillRect(a, top, Math.max(2, b - a), height);
        ctx.strokeStyle = "#7f7f7f"; ctx.lineWidth = 1; ctx.strokeRect(a, top, Math.max(2, b - a), height);
      });
      ctx.restore();
    } } };
  }

  function marksPlugin(marks) {
    // Unreadable spans shaded, each mark a vertical line: the moments a parameter became
    // protected / non-existent and became readable again.
    return { hooks: { draw: function (u) {
      var ctx = u.ctx, top = u.bbox.top, height = u.bbox.height, open = null;
      ctx.save();
      marks.forEach(function (mark) {
        var x = u.valToPos(at(mark[0]), "x", true);
        var again = mark[1].indexOf("readable again") === 0;
        if (!again && open === null) { open = x; }
        if (again && open !== null) {
          ctx.fillStyle = "rgba(214,39,40,0.10)"; ctx.fillRect(open, top, x - open, height); open = null;
        }
        ctx.strokeStyle = again ? "#2ca02c" : "#d62728"; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.moveTo(x, top); ctx.lineTo(x, top + height); ctx.stroke();
      });
      if (open !== null) {
        ctx.fillStyle = "rgba(214,39,40,0.10)"; ctx.fillRect(open, top, u.bbox.left + u.bbox.width - open, height);
      }
      ctx.restore();
    } } };
  }

  function trend(el, p) {
    var labels = p.labels || {};
    var keys = Object.keys(labels).map(Number).sort(function (a, b) { return a - b; });
    var axis = yAxis({}), shown = shortLabels(labels);
    // Enumerations, and setpoints hold until written again (a holding register: no input register is written).
    var step = p.step || (p.table === "holding" && written[p.slave + ":" + p.address]);
    if (p.step && keys.length && keys.length <= 16) {
      axis.splits = function () { return keys; };
      axis.values = function (u, splits) {
        return splits.map(function (v) { var t = shown[v]; return t === undefined ? String(v) : t; });
      };
    } else if (p.unit) {
      axis.label = p.unit;
    }
    var x = xs(p.x), y = p.y.slice();
    var opts = {
      width: width(el), height: 180,
      scales: { x: xScale() },
      axes: [xAxis(), axis],
      legend: { show: true },
      plugins: [marksPlugin(p.marks)],
      series: [{}, {
        label: p.code || p.label || String(p.address), stroke: "#1f77b4", width: 1.5,
        paths: step ? uPlot.paths.stepped({ align: 1 }) : undefined,
        // (a scaled value with the decimals its scale is written with, as the table: `30.0 Hz`)
        value: function (u, v) {
          if (v == null) { return "-"; }
          if (labels[v] !== undefined) { return v + " " + labels[v]; }
          return (p.decimals ? v.toFixed(p.decimals) : v) + (p.unit ? " " + p.unit : "");
        }
      }]
    };
    new uPlot(chartOptions(opts), [x, y], el);
    el.setAttribute("data-drawn", "uplot");
    if (step) { el.setAttribute("data-step", "1"); }
    if (p.step && keys.length) { el.setAttribute("data-labels", JSON.stringify(keys.map(function (k) { return shown[k]; }))); }
  }

  function responses(el, s) {
    var bands = (data.outages || []).filter(function (o) { return o.slave === s.slave; });
    new uPlot(chartOptions({
      width: width(el), height: 180, scales: { x: xScale() }, axes: [xAxis(), yAxis({ label: "ms" })],
      plugins: [bandsPlugin(bands)], legend: { show: true },
      series: [{}, { label: "slave " + s.slave + " response ms", stroke: "#1f77b4", width: 1,
                     points: { show: true, size: 3 } }]
    }), [xs(s.x), s.y], el);
    el.setAttribute("data-drawn", "uplot");
    el.setAttribute("data-outages", String(bands.length));
  }

  function load(el) {
    new uPlot(chartOptions({
      width: width(el), height: 150,
      scales: { x: xScale(), y: { range: function () { return [0, 100]; } } },
      axes: [xAxis(), yAxis({ label: "% of the minute" })], legend: { show: true },
      series: [{}, { label: "load %", stroke: "#2ca02c", fill: "rgba(44,160,44,0.2)", paths: uPlot.paths.stepped({ align: 1 }) }]
    }), [xs(data.load.x), data.load.y], el);
    el.setAttribute("data-drawn", "uplot");
  }

  function histogram(el, slave) {
    var t = slave.time;
    new uPlot({
      width: width(el), height: 160,
      scales: { x: { time: false }, y: { range: function (u, min, max) { return [0, Math.max(1, max)]; } } },
      legend: { show: false },
      axes: [{ label: "ms" }, { label: "answers" }],
      series: [{ label: "ms" }, { label: "answers", fill: "rgba(31,119,180,0.4)", stroke: "#1f77b4",
                 paths: uPlot.paths.bars({ size: [0.9, 60] }), points: { show: false } }]
    }, [t.bins, t.counts], el);
    el.setAttribute("data-drawn", "uplot");
    var p = document.createElement("p");
    p.className = "note";
    p.textContent = "min " + (t.min * 1000).toFixed(1) + " ms, median " + (t.median * 1000).toFixed(1) +
      " ms, p95 " + (t.p95 * 1000).toFixed(1) + " ms, max " + (t.max * 1000).toFixed(1) + " ms";
    el.appendChild(p);
  }

  function timeline(el) {
    var tables = data.event_columns.map(function (c) { return [c.x, c.n]; });
    var joined = uPlot.join(tables);
    joined[0] = xs(Array.prototype.slice.call(joined[0]));
    if (!joined[0].length) { el.appendChild(document.createTextNode("No events.")); return; }
    var series = [{}].concat(data.event_columns.map(function (c) {
      return { label: c.kind, stroke: COLORS[c.kind], paths: function () { return null; },
               points: { show: true, size: 7, fill: COLORS[c.kind] } };
    }));
    new uPlot(chartOptions({ width: width(el), height: 200, scales: { x: xScale() }, axes: [xAxis(), yAxis({ label: "events" })],
                series: series }), joined, el);
    el.setAttribute("data-drawn", "uplot");
  }

  document.querySelectorAll(".chart.rt").forEach(function (el) {
    var slave = Number(el.getAttribute("data-slave"));
    data.slaves.forEach(function (s) { if (s.slave === slave && s.time) { histogram(el, s); } });
  });
  document.querySelectorAll(".chart.rtt").forEach(function (el) {
    var slave = Number(el.getAttribute("data-slave"));
    (data.responses || []).forEach(function (s) { if (s.slave === slave) { responses(el, s); } });
  });
  document.querySelectorAll(".chart.load").forEach(load);
  document.querySelectorAll(".chart.timeline").forEach(timeline);
  document.querySelectorAll(".chart.trend").forEach(function (el) {
    trend(el, data.parameters[Number(el.getAttribute("data-index"))]);
  });
  document.body.setAttribute("data-charts", String(document.querySelectorAll(".uplot").length));
})();
