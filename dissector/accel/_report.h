/* --report fed by the engine (issue 28): for each transaction the engine counts (_stats.h count_transaction,
 * when a Report is attached to the Stats), what render/report/collect.py ReportCollector.add and .state and
 * render/report/health.py Health.add_items do with its frames: the x axis (the frame's time, its number when
 * untimed) and its doublings, the unanswered and exception events, a point per value read or confirmed
 * written in its series' Columns (_columns.h), the response times per slave. (The setpoints written are the
 * parameter table's: html.py asks Stats.writes.)
 * The Python objects keep the state: their scalars are taken at the start of each engine run (pull) and
 * given back at its end (push); the rare steps that need Python call their methods (a series' first value
 * and each value first seen: y as the device scales it, code, unit, labels, ReportCollector.engine_point;
 * an event, a doubling, a span readable again). collect.py stays the reference (VW3_PURE_PYTHON=1).
 * Times stay a model.Stamp where the Python stages have one (Time, _bus.h): x - origin is exact. */

#define REPORT_POINTS (1 << 16) /* y of (namer epoch, function, slave, address, value) kept at most */

typedef struct {
    uint32_t key;             /* param_key (_stats.h): by slave, address, table */
    int readable;             /* series.status was None when read (gen: while no span opened since) */
    uint8_t origins;          /* the protocol tables of the codes whose values it drew (told to series.origins) */
    unsigned gen;
    unsigned long long values; /* points not yet added to series.values */
    uint64_t last;            /* the point key of its last value (most polls read what they read before), */
    double last_y;            /* and its y */
    unsigned long long naming; /* the slave's naming its series last adopted (engine_point) */
    PyObject *series;         /* owned once kept (columns set); borrowed or NULL before */
    Columns *columns;         /* owned: series.columns; NULL: the series not kept yet */
} Trend;

typedef struct {
    uint64_t key;
    double y;
} Point;

static const DenseKind TREND_KIND = {sizeof(Trend), sizeof(uint32_t), 96, param_hash}; /* (a param_key) */
static const DenseKind POINT_KIND = {sizeof(Point), sizeof(uint64_t), 768, key_hash};

/* An x axis of COLUMNS pixel columns, ReportCollector's or Health's: from its first x, doubled by the
 * Python side (_double) whenever an x reaches its limit. */
typedef struct {
    Time origin;
    double width, limit;
} Axis;

typedef struct {
    PyObject_HEAD
    PyObject *collector, *health, *stamp, *exception; /* exception(slave, function, code, request): its event */
    PyObject *series, *h_series; /* their containers */
    int timed;   /* -1: not known yet */
    Time first, last;
    Axis axis, h_axis; /* the collector's and health's */
    unsigned long long number, dropped;
    unsigned long long numbered; /* the frames of the files before (several files one bus: collect.py new_input) */
    Columns *h_columns[256];
    Dense trends; /* of Trend: the series kept (MAX_SERIES) */
    Dense points; /* of Point */
    PyObject *namers[256]; /* the namer each slave's cached points were read with */
    unsigned epochs[256];
    unsigned long long namings, named[256]; /* namer changes, and the count at each slave's last one */
    unsigned gen;
    unsigned long long spans; /* ReportCollector.spans when last pulled */
    int full; /* the collector holds MAX_SERIES series, every one in `trends` */
} Report;

static PyTypeObject ReportType;

static PyObject *time_object(Report *r, const Time *t) {
    if (!t->has) Py_RETURN_NONE;
    return t->exact ? PyObject_CallFunction(r->stamp, "L", t->ns) : PyFloat_FromDouble(t->d);
}

static int set_attr(PyObject *o, const char *name, PyObject *value) {
    int status = value == NULL ? -1 : PyObject_SetAttrString(o, name, value);
    Py_XDECREF(value);
    return status;
}

/* o.name += more (nothing for 0): 0, or -1 with an exception set. */
static int attr_add(PyObject *o, const char *name, unsigned long long more) {
    PyObject *had = more ? PyObject_GetAttrString(o, name) : NULL, *n = had ? PyLong_FromUnsignedLongLong(more) : NULL;
    int status = !more ? 0 : set_attr(o, name, n ? PyNumber_Add(had, n) : NULL);
    Py_XDECREF(had);
    Py_XDECREF(n);
    return status;
}

/* The scalars of the collector and of health kept here while the engine runs: taken when a run starts and
 * after a Python method changed them (pull), given back before one is called and when the run ends (push). */
enum { AS_TIME, AS_FLOAT, AS_FLAG, AS_COUNT }; /* AS_FLAG: None, False or True as -1, 0 or 1 */
static const struct {
    int health, as;
    const char *name;
    size_t at;
} scalars[] = {
    {0, AS_FLAG, "timed", offsetof(Report, timed)},       {0, AS_TIME, "origin", offsetof(Report, axis.origin)},
    {0, AS_TIME, "first_x", offsetof(Report, first)},     {0, AS_TIME, "last_x", offsetof(Report, last)},
    {0, AS_FLOAT, "width", offsetof(Report, axis.width)}, {0, AS_FLOAT, "limit", offsetof(Report, axis.limit)},
    {0, AS_COUNT, "number", offsetof(Report, number)},    {0, AS_COUNT, "spans", offsetof(Report, spans)},
    {0, AS_COUNT, "numbered", offsetof(Report, numbered)},
    {1, AS_TIME, "origin", offsetof(Report, h_axis.origin)}, {1, AS_FLOAT, "width", offsetof(Report, h_axis.width)},
    {1, AS_FLOAT, "limit", offsetof(Report, h_axis.limit)},
};
#define SCALARS (sizeof scalars / sizeof *scalars)

static int report_pull(Report *r) {
    unsigned long long spans = r->spans; /* unreadable spans the Python stages opened: statuses read again */
    for (size_t k = 0; k < SCALARS; k++) {
        PyObject *o = scalars[k].health ? r->health : r->collector, *v;
        char *at = (char *)r + scalars[k].at;
        if (o == Py_None) continue;
        if ((v = PyObject_GetAttrString(o, scalars[k].name)) == NULL) return -1;
        switch (scalars[k].as) {
        case AS_TIME: (void)read_time(v, (Time *)at); break;
        case AS_FLOAT: *(double *)at = PyFloat_AsDouble(v); break;
        case AS_FLAG: *(int *)at = v == Py_None ? -1 : PyObject_IsTrue(v); break;
        default: *(unsigned long long *)at = PyLong_AsUnsignedLongLong(v);
        }
        Py_DECREF(v);
        if (PyErr_Occurred()) return -1;
    }
    if (spans != r->spans) r->gen++;
    return 0;
}

static PyObject *scalar_value(Report *r, size_t k) {
    const char *at = (const char *)r + scalars[k].at;
    switch (scalars[k].as) {
    case AS_TIME: return time_object(r, (const Time *)at);
    case AS_FLOAT: return PyFloat_FromDouble(*(const double *)at);
    case AS_FLAG: return *(const int *)at < 0 ? Py_NewRef(Py_None) : PyBool_FromLong(*(const int *)at);
    default: return PyLong_FromUnsignedLongLong(*(const unsigned long long *)at);
    }
}

/* ... and back; `counts`: the counts kept here instead (series values, dropped: sums, which the Python
 * stages add to as well, given back once at the end). Health's answers per slave are bustiming's count. */
static int report_push(Report *r, int counts) {
    for (size_t k = 0; !counts && k < SCALARS; k++) {
        PyObject *o = scalars[k].health ? r->health : r->collector;
        if (o != Py_None && set_attr(o, scalars[k].name, scalar_value(r, k)) < 0) return -1;
    }
    if (!counts) return 0;
    for (size_t k = 0; k <= r->trends.count; k++) { /* k == count: the collector's series_dropped */
        Trend *t = k < r->trends.count ? (Trend *)r->trends.items + k : NULL;
        unsigned long long *n = t != NULL ? &t->values : &r->dropped;
        if (attr_add(t != NULL ? t->series : r->collector, t != NULL ? "values" : "series_dropped", *n) < 0) return -1;
        *n = 0;
    }
    return 0;
}

/* A Python method's result: 0 (the scalars taken again after it, with `pull`), or -1. */
static int report_called(Report *r, PyObject *result, int pull) {
    if (result == NULL) return -1;
    Py_DECREF(result);
    return pull ? report_pull(r) : 0;
}

/* target.method(args of a Py_BuildValue format, NULL: none) with the scalars given back first. */
#define report_call(r, target, method, pull, ...) \
    (report_push(r, 0) < 0 ? -1 : report_called(r, PyObject_CallMethod(target, method, __VA_ARGS__), pull))

/* x on the axis `a` of `owner` (the collector or health), which doubles it until x falls in it: 0 or -1. */
static int axis_reach(Report *r, Axis *a, PyObject *owner, const Time *x) {
    if (!a->origin.has) {
        a->origin = *x;
        a->limit = x->d + COLUMNS * a->width;
    }
    while (x->d >= a->limit)
        if (report_call(r, owner, "_double", 1, NULL) < 0) return -1;
    return 0;
}

static long long axis_col(const Axis *a, const Time *x) {
    long long col = (long long)(time_sub(x, &a->origin) / a->width);
    return col > 0 ? col : 0;
}

/* ReportCollector._x: the x of the frame numbered `number` in its file (its time, or its number on from the files
 * before, untimed). */
static int report_x(Report *r, int timed, long long ns, unsigned long long number, Time *x) {
    number += r->numbered;
    r->number = number;
    if (r->timed < 0) {
        r->timed = timed;
        r->axis.width = timed ? TIMED_WIDTH : UNTIMED_WIDTH;
    }
    *x = !r->timed ? (Time){1, 0, 0, (double)number} : timed ? stamp_time(1, ns) : (Time){1, 0, 0, 0.0};
    if (axis_reach(r, &r->axis, r->collector, x) < 0) return -1;
    if (!r->first.has) r->first = *x;
    if (!r->last.has || x->d > r->last.d) r->last = *x;
    return 0;
}

/* ReportCollector._event: `text` a new reference (NULL: an error). */
static int report_event(Report *r, const Time *x, const char *kind, int slave, PyObject *text) {
    PyObject *at = text != NULL ? time_object(r, x) : NULL;
    int status = at != NULL ? report_call(r, r->collector, "_event", 0, "(OsiO)", at, kind, slave, text) : -1;
    Py_XDECREF(at);
    Py_XDECREF(text);
    return status;
}

/* `o` (a new reference, or NULL) as compiled Columns: NULL with an exception set when it is not. */
static Columns *as_columns(PyObject *o, const char *what) {
    if (o != NULL && !PyObject_TypeCheck(o, &ColumnsType)) {
        Py_CLEAR(o);
        PyErr_Format(PyExc_TypeError, "%s: compiled Columns expected", what);
    }
    return (Columns *)o;
}

/* Health._point: a response time `y` of `slave` at `x`. */
static int health_point(Report *r, int slave, const Time *x, double y) {
    if (r->health == Py_None) return 0;
    if (axis_reach(r, &r->h_axis, r->health, x) < 0) return -1;
    if (r->h_columns[slave] == NULL) { /* its series' columns, made unless the Python stages made them */
        PyObject *key = PyLong_FromLong(slave), *made = key ? PyObject_CallNoArgs((PyObject *)&ColumnsType) : NULL;
        PyObject *columns = made ? Py_XNewRef(PyDict_SetDefault(r->h_series, key, made)) : NULL;
        Py_XDECREF(made);
        Py_XDECREF(key);
        if ((r->h_columns[slave] = as_columns(columns, "Health.series")) == NULL) return -1;
    }
    return columns_point(r->h_columns[slave], axis_col(&r->h_axis, x), x->d, y);
}

/* The series of trend t known from now on (its columns kept). */
static int trend_keep(Report *r, Trend *t, PyObject *series) {
    Columns *columns = as_columns(PyObject_GetAttrString(series, "columns"), "Series.columns");
    if (columns == NULL) return -1;
    t->series = Py_NewRef(series);
    t->columns = columns;
    t->gen = r->gen - 1;
    return 0;
}

/* The collector keeps MAX_SERIES series: every one of them known here, so that a key not known is of no
 * series without a look-up (the max-size mix reads thousands of addresses once each). */
static int trends_full(Report *r) {
    PyObject *key, *series;
    Py_ssize_t at = 0;
    int slave, table, address;
    while (PyDict_Next(r->series, &at, &key, &series)) {
        if (!PyArg_ParseTuple(key, "iii", &slave, &address, &table)) return -1;
        uint32_t k = param_key(slave, table, (unsigned)address);
        Trend *t = dense_find(&r->trends, &TREND_KIND, &k);
        if (t == NULL && (t = dense_add(&r->trends, &TREND_KIND, &k, 0)) == NULL) return -1;
        if (t->columns == NULL && trend_keep(r, t, series) < 0) return -1;
    }
    r->full = 1;
    return 0;
}

/* A trend's references released (a series not kept yet is borrowed: none). */
static void trend_release(Trend *t) {
    if (t->columns != NULL) CLEAR_ALL(&t->series, (PyObject **)&t->columns);
}

/* A new device for this slave (its namer another: profile `auto`): its trends forgotten (zeroed in place: key 0,
 * a series' never, no look-up finds it), their values counted into their series, which the collector may have
 * moved to other tables (ReportCollector.rehomed): the next value finds its series again; its values are read
 * again (the points cached with the old namer not asked). 0, or -1 with an exception set. */
static int report_device(Report *r, Slave *s, int slave) {
    int status = 0;
    for (Trend *t = (Trend *)r->trends.items; t < (Trend *)r->trends.items + r->trends.count; t++) {
        if ((int)PARAM_SLAVE(t->key) != slave) continue;
        if (t->columns != NULL && status == 0) status = attr_add(t->series, "values", t->values);
        trend_release(t);
        memset(t, 0, sizeof *t);
        r->full = 0;
    }
    Py_XSETREF(r->namers[slave], Py_XNewRef(s->namer));
    r->named[slave] = ++r->namings;
    if (++r->epochs[slave] >= 1u << 16) {
        dense_clear(&r->points);
        memset(r->epochs, 0, sizeof r->epochs);
    }
    return status;
}

/* ReportCollector.state of a value read or confirmed written (READ, CONFIRM) at x, in column col; `table`:
 * the function's register table on the slave's device (Stats.tables), `origin`: in the protocol. */
static int report_value(Report *r, Slave *s, int slave, int function, int table, int origin, unsigned address,
                        unsigned value, const Time *x, long long col) {
    if (s->namer != r->namers[slave] && report_device(r, s, slave) < 0) return -1;
    uint32_t tag = param_key(slave, table, address);
    Trend *t = dense_find(&r->trends, &TREND_KIND, &tag);
    if (t == NULL && !r->full && PyDict_Size(r->series) >= MAX_SERIES) {
        if (trends_full(r) < 0) return -1;
        t = dense_find(&r->trends, &TREND_KIND, &tag);
    }
    if (t == NULL && r->full) { /* none kept: never one */
        r->dropped++;
        return 0;
    }
    if (t == NULL && (t = dense_add(&r->trends, &TREND_KIND, &tag, 0)) == NULL) return -1;
    if (t->columns == NULL) {
        PyObject *key = Py_BuildValue("(iIi)", slave, address, table), *series = key ? PyDict_GetItemWithError(r->series, key) : NULL;
        Py_XDECREF(key);
        if (series == NULL && PyErr_Occurred()) return -1;
        t->series = series; /* NULL: made by engine_point below (there is room: not full) */
    }
    int mapped = bit(s->mapped, address);
    uint64_t pkey = 1ULL << 63 | (uint64_t)r->epochs[slave] << 46 | (uint64_t)handled_index(function) << 40 |
                    (uint64_t)slave << 32 | (uint64_t)address << 16 | value;
    Point *p = NULL;
    int keep_point = 0; /* a mapped value first seen: its y kept */
    double y = value; /* an address the device does not name: the raw word */
    /* Asked: a value first seen (engine_point adopts the device's map row for its series: its points read
     * again when the slave's device changed), and an address the device does not name, once a change. */
    int ask = t->series == NULL;
    if (mapped && t->last == pkey) {
        y = t->last_y;
    } else if (mapped) {
        if ((p = dense_find(&r->points, &POINT_KIND, &pkey)) != NULL) y = p->y;
        else ask = keep_point = 1;
    } else if (t->naming != r->named[slave]) {
        ask = 1;
    }
    if (ask) {
        PyObject *answer = PyObject_CallMethod(r->collector, "engine_point", "iiIIi", slave, function, address, value,
                                               t->naming != r->named[slave]);
        if (answer == NULL) return -1;
        PyObject *series = PyTuple_Check(answer) && PyTuple_GET_SIZE(answer) == 2 ? PyTuple_GET_ITEM(answer, 0) : NULL;
        y = series != NULL ? PyFloat_AsDouble(PyTuple_GET_ITEM(answer, 1)) : -1.0;
        if (series != NULL && t->series == NULL) t->series = series;
        else if (series == NULL) PyErr_SetString(PyExc_TypeError, "engine_point must return (series, y)");
        Py_DECREF(answer);
        if (PyErr_Occurred()) return -1;
        t->naming = r->named[slave];
        if (keep_point && r->points.count < REPORT_POINTS) {
            if ((p = dense_add(&r->points, &POINT_KIND, &pkey, REPORT_POINTS)) == NULL) return -1;
            p->y = y;
        }
    }
    if (t->columns == NULL && trend_keep(r, t, t->series) < 0) return -1;
    if (!(t->origins >> origin & 1)) { /* a code of another table draws it: Series.origins says so (rehome) */
        PyObject *had = PyObject_GetAttrString(t->series, "origins");
        long bits = had != NULL ? PyLong_AsLong(had) : -1;
        Py_XDECREF(had);
        if ((bits == -1 && PyErr_Occurred()) || set_attr(t->series, "origins", PyLong_FromLong(bits | 1L << origin)) < 0)
            return -1;
        t->origins = (uint8_t)(bits | 1L << origin);
    }
    if (t->gen != r->gen) {
        PyObject *status = PyObject_GetAttrString(t->series, "status");
        if (status == NULL) return -1;
        t->readable = status == Py_None;
        t->gen = r->gen;
        Py_DECREF(status);
    }
    if (!t->readable) {
        PyObject *at = time_object(r, x);
        int status = at != NULL ? report_call(r, r->collector, "_readable_again", 0, "(OO)", t->series, at) : -1;
        Py_XDECREF(at);
        if (status < 0) return -1;
        t->readable = 1;
    }
    t->values++;
    t->last = pkey, t->last_y = y;
    return columns_point(t->columns, col, x->d, y);
}

/* What the report takes of a transaction the engine counts (see count_transaction): number, number + 1;
 * `table`: its registers' table on the slave's device (Stats.tables), `origin`: in the protocol. */
static int report_transaction(PyObject *report, Slave *s, const uint8_t *b, const FrameRef *qf, const FrameRef *af,
                              const Words *confirmed, const Words *reads, unsigned long long number, int table,
                              int origin) {
    Report *r = (Report *)report;
    const uint8_t *q = b + qf->at, *a = af != NULL ? b + af->at : NULL;
    int slave = q[0], function = q[1];
    Time x;
    if (report_x(r, qf->timed, qf->ns, number, &x) < 0) return -1;
    if (a == NULL) return report_event(r, &x, "unanswered", slave, PyUnicode_FromFormat("function %d unanswered", function));
    if (report_x(r, af->timed, af->ns, number + 1, &x) < 0) return -1;
    Time at = stamp_time(1, af->ns);
    if (qf->timed && af->timed && health_point(r, slave, &at, stamp_seconds(af->ns, qf->ns)) < 0) return -1;
    if (a[1] & 0x80) /* (its request: the meaning may depend on it, reportfeed.py exception_event) */
        return report_event(r, &x, "exception", slave, PyObject_CallFunction(r->exception, "iiiy#", slave, function,
                                                                             a[2], q, qf->length));
    long long col = axis_col(&r->axis, &x);
    for (int pass = 0; pass < 2; pass++) { /* the writes confirmed first (FC23 writes before it reads) */
        const Words *w = pass ? reads : confirmed;
        for (unsigned k = 0; w != NULL && k < w->count; k++)
            if (report_value(r, s, slave, function, table, origin, words_address(w, k), words_value(w, k), &x, col) < 0)
                return -1;
    }
    return 0;
}

/* ---- the Python object ------------------------------------------------------------------------- */
static int report_init(Report *r, PyObject *args, PyObject *kwargs) {
    static char *keywords[] = {"collector", "health", "stamp", "exception", NULL};
    PyObject *objects[4];
    if (r->collector != NULL) return fail(PyExc_RuntimeError, "Report is initialised once");
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOO", keywords, &objects[0], &objects[1], &objects[2], &objects[3]))
        return -1;
    r->collector = objects[0], r->health = objects[1], r->stamp = objects[2], r->exception = objects[3];
    for (int k = 0; k < 4; k++) Py_INCREF(objects[k]);
    r->series = PyObject_GetAttrString(r->collector, "series");
    if (r->health != Py_None) r->h_series = PyObject_GetAttrString(r->health, "series");
    if (r->series == NULL || (r->health != Py_None && r->h_series == NULL)) return -1;
    return report_pull(r);
}

static void report_dealloc(Report *r) {
    for (Trend *t = (Trend *)r->trends.items; t < (Trend *)r->trends.items + r->trends.count; t++) trend_release(t);
    for (int k = 0; k < 256; k++) CLEAR_ALL((PyObject **)&r->h_columns[k], &r->namers[k]);
    dense_free(&r->trends);
    dense_free(&r->points);
    CLEAR_ALL(&r->collector, &r->health, &r->stamp, &r->exception, &r->series, &r->h_series);
    Py_TYPE(r)->tp_free((PyObject *)r);
}

static PyObject *report_pull_method(Report *r, PyObject *unused) { return report_pull(r) < 0 ? NULL : Py_NewRef(Py_None); }
static PyObject *report_push_method(Report *r, PyObject *args) {
    int counts = 0;
    return !PyArg_ParseTuple(args, "|p", &counts) || report_push(r, counts) < 0 ? NULL : Py_NewRef(Py_None);
}

static PyMethodDef report_methods[] = {
    {"pull", (PyCFunction)report_pull_method, METH_NOARGS, "take the collector's and health's state (a run starts)"},
    {"push", (PyCFunction)report_push_method, METH_VARARGS,
     "push(counts=False): give it back (a run ended); push(True): the counts kept here (sums), at the end"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject ReportType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "dissector.accel._summary.Report",
    .tp_basicsize = sizeof(Report),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Report(collector, health, stamp, exception): --report fed by the engine (render/report/collect.py,\n"
              "health.py; their COLUMNS and MAX_SERIES from _tables.h); set as Stats.report.",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)report_init,
    .tp_dealloc = (destructor)report_dealloc,
    .tp_methods = report_methods,
};

/* Stats.report = a Report or None (_stats.h: count_transaction feeds it). */
static int stats_set_report(Stats *st, PyObject *value, void *closure) {
    if (value != NULL && value != Py_None && !PyObject_TypeCheck(value, &ReportType))
        return fail(PyExc_TypeError, "report: a Report or None");
    Py_XSETREF(st->report, value != NULL && value != Py_None ? Py_NewRef(value) : NULL);
    return 0;
}
