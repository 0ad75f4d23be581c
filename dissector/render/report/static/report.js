// Draws the report's charts from the JSON block with uPlot; the tables are already in the page.
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("report-data").textContent);
  var origin = data.origin, timed = data.timed;
  var COLORS = { exception: "#d62728", protection: "#9467bd", crc: "#ff7f0e", noise: "#8c564b",
                 silence: "#17becf", unanswered: "#7f7f7f" };

  function width(el) { return Math.max(320, Math.min(1100, (el.clientWidth || 900) - 10)); }
  function xs(list) { return list.map(function (x) { return x + origin; }); }
  // Every chart spans the whole capture, so that moments line up from chart to chart.
  var x0 = origin, x1 = origin + data.span;
  if (x1 <= x0) { x1 = x0 + 1; }
  function xScale() { return { time: timed, range: function () { return [x0, x1]; } }; }
  function xAxis() { return timed ? {} : { label: "frame" }; }

  function marksPlugin(marks) {
    // Unreadable spans shaded, each mark a vertical line: the moments a parameter became
    // protected / non-existent and became readable again.
    return { hooks: { draw: function (u) {
      var ctx = u.ctx, top = u.bbox.top, height = u.bbox.height, open = null;
      ctx.save();
      marks.forEach(function (mark) {
        var x = u.valToPos(mark[0] + origin, "x", true);
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
    var yAxis = { size: p.step ? 190 : 60 };
    if (p.step && keys.length && keys.length <= 16) {
      yAxis.splits = function () { return keys; };
      yAxis.values = function (u, splits) {
        return splits.map(function (v) { var t = labels[v]; return t === undefined ? String(v) : (t.length > 26 ? t.slice(0, 25) + "…" : t); });
      };
    } else if (p.unit) {
      yAxis.label = p.unit;
    }
    var x = xs(p.x), y = p.y.slice();
    var opts = {
      width: width(el), height: 180,
      scales: { x: xScale() },
      axes: [xAxis(), yAxis],
      legend: { show: true },
      plugins: [marksPlugin(p.marks)],
      series: [{}, {
        label: p.code || String(p.address), stroke: "#1f77b4", width: 1.5,
        paths: p.step ? uPlot.paths.stepped({ align: 1 }) : undefined,
        value: function (u, v) { return v == null ? "-" : (labels[v] !== undefined ? v + " " + labels[v] : v + (p.unit ? " " + p.unit : "")); }
      }]
    };
    new uPlot(opts, [x, y], el);
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
    new uPlot({ width: width(el), height: 200, scales: { x: xScale() }, axes: [xAxis(), { label: "events" }],
                series: series }, joined, el);
    el.setAttribute("data-drawn", "uplot");
  }

  document.querySelectorAll(".chart.rt").forEach(function (el) {
    var slave = Number(el.getAttribute("data-slave"));
    data.slaves.forEach(function (s) { if (s.slave === slave && s.time) { histogram(el, s); } });
  });
  document.querySelectorAll(".chart.timeline").forEach(timeline);
  document.querySelectorAll(".chart.trend").forEach(function (el) {
    trend(el, data.parameters[Number(el.getAttribute("data-index"))]);
  });
  document.body.setAttribute("data-charts", String(document.querySelectorAll(".uplot").length));
})();
