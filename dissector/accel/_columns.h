/* --report's pixel columns of one parameter series (render/report/columns.py `Columns`, which stays the
 * reference under VW3_PURE_PYTHON=1): 8 doubles a column, the first, lowest, highest and last point
 * (fx fy nx ny mx my lx ly), in a growing array. The same arithmetic as the Python class, step for
 * step, so that the page is byte-identical: add() is once per register value of the capture, compact()
 * and drawn_json() once per series and doubling. Included by _summary.c: one translation unit. */

typedef struct {
    PyObject_HEAD
    double *d;
    Py_ssize_t n;      /* doubles used */
    size_t cap;        /* doubles allocated */
    long long col;     /* the open column; -1 once closed */
} Columns;

static PyTypeObject ColumnsType;

static int columns_grow(Columns *self, Py_ssize_t need) {
    if ((size_t)need <= self->cap) return 0;
    size_t cap = self->cap ? self->cap : 64; /* doubled up to 64 columns, then 8 more at a time: */
    while (cap < (size_t)need) cap += cap < 512 ? cap : 64; /* a series' COLUMNS + 1 columns fill 38 KB, not 64 */
    return resize(&self->d, &self->cap, cap, sizeof *self->d);
}

static int columns_init(Columns *self, PyObject *args, PyObject *kwargs) {
    self->col = -1;
    self->n = 0;
    return 0;
}

static void columns_dealloc(Columns *self) {
    PyMem_Free(self->d);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Column `c` merged into column `o` (a later one, or a point as a column of four equal points): its lowest
 * and highest points where they pass o's, its last point. */
static inline void column_merge(double *o, const double *c) {
    if (c[3] < o[3]) o[2] = c[2], o[3] = c[3];
    if (c[5] > o[5]) o[4] = c[4], o[5] = c[5];
    o[6] = c[6], o[7] = c[7];
}

/* The point (x, y) in column col (a new column: the point as its four points): 0, or -1 with an
 * exception set (no memory). */
static int columns_point(Columns *self, long long col, double x, double y) {
    const double point[8] = {x, y, x, y, x, y, x, y};
    if (col == self->col) {
        column_merge(self->d + self->n - 8, point);
        return 0;
    }
    self->col = col;
    if (columns_grow(self, self->n + 8) < 0) return -1;
    memcpy(self->d + self->n, point, sizeof point);
    self->n += 8;
    return 0;
}

static PyObject *columns_add(Columns *self, PyObject *const *args, Py_ssize_t nargs) {
    if (nargs != 3) return PyErr_Format(PyExc_TypeError, "add(col, x, y)");
    long long col = PyLong_AsLongLong(args[0]);
    double x = PyFloat_AsDouble(args[1]), y = PyFloat_AsDouble(args[2]);
    if (PyErr_Occurred() || columns_point(self, col, x, y) < 0) return NULL;
    Py_RETURN_NONE;
}

static PyObject *columns_close(Columns *self, PyObject *unused) {
    self->col = -1;
    Py_RETURN_NONE;
}

static Py_ssize_t columns_len(Columns *self) { return self->n / 8; }

/* Merge the finished columns that fall in one column of `width` (Python's int() truncates as the cast). */
static PyObject *columns_compact(Columns *self, PyObject *args) {
    double origin, width;
    if (!PyArg_ParseTuple(args, "dd", &origin, &width)) return NULL;
    double *d = self->d;
    Py_ssize_t out = 0;
    long long last = 0;
    for (Py_ssize_t i = 0; i < self->n; i += 8) {
        long long col = (long long)((d[i] - origin) / width);
        if (out == 0 || col != last) {
            if (out != i) memmove(d + out, d + i, 8 * sizeof(double));
            out += 8;
            last = col;
            continue;
        }
        column_merge(d + out - 8, d + i);
    }
    self->n = out;
    Py_RETURN_NONE;
}

static int point_equal(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* round(v, digits) as Python's float.__round__ does it: the decimal text correctly rounded (dtoa's
 * mode 3, as PyOS_double_to_string's 'f'), read back correctly rounded. */
static int round_to(double v, int digits, double *r) {
    *r = v;
    if (!isfinite(v)) return 0;
    char *text = PyOS_double_to_string(v, 'f', digits, 0, NULL);
    if (text == NULL) return -1;
    *r = PyOS_string_to_double(text, NULL, NULL);
    PyMem_Free(text);
    return *r == -1.0 && PyErr_Occurred() ? -1 : 0;
}

/* round(v, digits) as json.dumps writes it into the page (its repr; a whole y: its int), after a comma
 * unless first. Between 1e-4 and 1e9 the repr of the rounded value is its fixed-point text (as the
 * rounding's dtoa makes it: fixed_text), trailing zeros dropped: no other decimal of `digits` digits or
 * fewer is within half an ulp of it. */

static void json_number(Out *o, double v, int digits, int whole) {
    char text[64];
    double a = fabs(v), r;
    if (o->data[o->len - 1] != '[') out_put(o, ",", 1);
    if (whole && a < 9e15) {
        if (v < 0) out_put(o, "-", 1);
        out_uint(o, (unsigned long long)a, 0);
    } else if (whole || (a != 0.0 && (a < 1e-4 || a >= 1e9))) {
        char *repr = round_to(v, whole ? 0 : digits, &r) < 0 ? NULL
                   : PyOS_double_to_string(r, whole ? 'f' : 'r', 0, whole ? 0 : Py_DTSF_ADD_DOT_0, NULL);
        if (repr == NULL) o->failed = 1;
        else out_cstr(o, repr);
        PyMem_Free(repr);
    } else {
        int n = fixed_text(text, v, digits);
        if (!digits) text[n++] = '.', text[n++] = '0'; /* (a float's repr: 12.0) */
        while (text[n - 1] == '0' && text[n - 2] != '.') n--;
        out_put(o, text, (size_t)n);
    }
}

/* drawn_json(origin, digits, scale=0, places=0): columns.py drawn()'s lists as JSON text: each column's
 * points in the order of their x, several at one x all (an FC23 write and its read back: a step), none
 * before the last x kept, a run of equal values by its ends only (Columns.points), x - origin rounded to
 * `digits`, y an int when whole, else rounded to Y_DIGITS, or y * scale rounded to `places`, as json.dumps
 * writes them; None when a value is not finite (columns.py drawn() then asks the Python Columns.points of
 * these columns' values()). */
static PyObject *columns_drawn_json(Columns *self, PyObject *args) {
    double origin, scale = 0.0;
    int digits, places = 0;
    if (!PyArg_ParseTuple(args, "di|di", &origin, &digits, &scale, &places)) return NULL;
    if (digits < 0 || digits > 9 || places < 0 || places > 9) return PyErr_Format(PyExc_ValueError, "digits 0..9");
    /* Kept points in C first (x, y), n / 2 + 1 each; made into JSON text at the end. */
    double *kx = PyMem_Malloc((size_t)(self->n + 2) * sizeof(double));
    if (kx == NULL) return PyErr_NoMemory();
    double *ky = kx + self->n / 2 + 1;
    Py_ssize_t kept = 0;
    for (Py_ssize_t i = 0; i < self->n; i += 8) {
        const double *c = self->d + i;
        /* Its first point, its lowest and highest unless one is the first or the last, its last unless it
         * is the first alone; sorted by x, stably (points at one x: in that order). */
        const double *ends[4] = {c};
        int count = 1;
        if (!point_equal(c + 2, c) && !point_equal(c + 2, c + 6)) ends[count++] = c + 2;
        if (!point_equal(c + 4, c) && !point_equal(c + 4, c + 6) && !point_equal(c + 4, c + 2)) ends[count++] = c + 4;
        if (!point_equal(c + 6, c) || count > 1) ends[count++] = c + 6;
        for (int j = 1; j < count; j++) {
            const double *p = ends[j];
            int at = j;
            for (; at > 0 && p[0] < ends[at - 1][0]; at--) ends[at] = ends[at - 1];
            ends[at] = p;
        }
        for (int j = 0; j < count; j++) {
            double x = ends[j][0], y = ends[j][1];
            if (kept && (x < kx[kept - 1] || (x == kx[kept - 1] && y == ky[kept - 1]))) continue;
            if (kept >= 2 && ky[kept - 1] == y && ky[kept - 2] == y) {
                kx[kept - 1] = x;
                continue;
            }
            kx[kept] = x, ky[kept] = y;
            kept++;
        }
    }
    Out text[2] = {{0}};
    int finite = 1;
    for (int k = 0; k < 2; k++) out_put(&text[k], "[", 1);
    for (Py_ssize_t j = 0; j < kept && finite; j++) {
        double x = kx[j] - origin, y = ky[j];
        if (!(finite = isfinite(x) && isfinite(scale != 0.0 ? y * scale : y))) break;
        json_number(&text[0], x, digits, 0);
        if (scale != 0.0) json_number(&text[1], y * scale, places, 0);
        else json_number(&text[1], y, Y_DIGITS, floor(y) == y);
    }
    for (int k = 0; k < 2; k++) out_put(&text[k], "]", 1);
    PyMem_Free(kx);
    PyObject *pair = NULL;
    if (!text[0].failed && !text[1].failed)
        pair = !finite ? Py_NewRef(Py_None)
                       : Py_BuildValue("(s#s#)", text[0].data, (Py_ssize_t)text[0].len, text[1].data,
                                       (Py_ssize_t)text[1].len);
    else if (!PyErr_Occurred())
        PyErr_NoMemory();
    PyMem_Free(text[0].data), PyMem_Free(text[1].data);
    return pair;
}

/* levels() -> (first y, lowest y, highest y), None when empty (columns.py Columns.levels). */
static PyObject *columns_levels(Columns *self, PyObject *unused) {
    if (!self->n) Py_RETURN_NONE;
    double low = self->d[1], high = self->d[1];
    for (Py_ssize_t i = 3; i < self->n; i += 2) {
        if (self->d[i] < low) low = self->d[i];
        if (self->d[i] > high) high = self->d[i];
    }
    return Py_BuildValue("(ddd)", self->d[1], low, high);
}

/* values() -> bytes and load(values): the doubles (8 a column) as bytes, for the rare rewrites (a profile
 * chosen later: reading.py remap) done in Python for both stores. */
static PyObject *columns_values(Columns *self, PyObject *unused) {
    return PyBytes_FromStringAndSize((const char *)self->d, self->n * (Py_ssize_t)sizeof(double));
}

static PyObject *columns_load(Columns *self, PyObject *values) {
    Py_buffer view;
    if (PyObject_GetBuffer(values, &view, PyBUF_SIMPLE) < 0) return NULL;
    Py_ssize_t n = view.len / (Py_ssize_t)sizeof(double);
    if (view.len % (8 * sizeof(double)) != 0) PyErr_SetString(PyExc_ValueError, "load(values): 8 doubles a column");
    else if (columns_grow(self, n) == 0) {
        if (n) memcpy(self->d, view.buf, (size_t)view.len); /* (no array yet when n is 0) */
        self->n = n;
    }
    PyBuffer_Release(&view);
    return PyErr_Occurred() ? NULL : Py_NewRef(Py_None);
}

static PyMethodDef columns_methods[] = {
    {"add", (PyCFunction)(void (*)(void))columns_add, METH_FASTCALL, "add(col, x, y): a point in column col"},
    {"close", (PyCFunction)columns_close, METH_NOARGS, "end the open column (the width is about to change)"},
    {"compact", (PyCFunction)columns_compact, METH_VARARGS, "compact(origin, width): merge columns now one"},
    {"drawn_json", (PyCFunction)columns_drawn_json, METH_VARARGS,
     "drawn_json(origin, digits, scale=0, places=0): columns.py drawn()'s lists as JSON text, None when one is not\n"
     "finite"},
    {"levels", (PyCFunction)columns_levels, METH_NOARGS, "(first y, lowest y, highest y), None when empty"},
    {"values", (PyCFunction)columns_values, METH_NOARGS, "the doubles as bytes, 8 a column"},
    {"load", (PyCFunction)columns_load, METH_O, "load(values): replace the doubles (bytes, an array('d'))"},
    {NULL, NULL, 0, NULL},
};

static PySequenceMethods columns_sequence = {.sq_length = (lenfunc)columns_len};

static PyTypeObject ColumnsType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "dissector.accel._summary.Columns",
    .tp_basicsize = sizeof(Columns),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "--report's pixel columns of one series (render/report/columns.py Columns).",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)columns_init,
    .tp_dealloc = (destructor)columns_dealloc,
    .tp_methods = columns_methods,
    .tp_as_sequence = &columns_sequence,
};
