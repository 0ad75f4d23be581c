/* --stats counted in the engine: the counts of render/stats.py's StatsCollector for the transactions
 * the engine shows, in one store that the Python stages' frames update too (render/stats.py calls
 * Stats.param/poll/poll_fail for theirs), so that a parameter's last value and its changes follow
 * the stream's order whichever side saw each frame. Included by _summary.c: one translation unit.
 *
 * What lives here: per (slave, address) the StatsCollector's ParameterStats (counts, last value, its
 * text, the code), per request key the PollCycle's count/misses/first frame (untimed input only: the
 * engine never sees timestamps), and per (slave, function) the engine's own counts (TALLY_COUNTS, read
 * through tallies()), which the collector adds to its own (sums: order does not matter). A last value seen here keeps the slave's
 * `namer` (SlaveFacts.namer: the device it was read with), asked for its text when the report is
 * made: a register's text is asked once per parameter, not once per value.
 *
 * Not tracked by the collector (GC): it holds texts, codes and namers (closures over a device),
 * none of which refer back to it.
 */

#include "_bus.h" /* the time-dependent counts: bus timing, response times, poll intervals */

typedef struct {
    uint32_t key; /* param_key: 1 << 27 | slave << 19 | address << 3 | table */
    uint32_t counts[PARAM_COUNTS]; /* by PARAM_* (c_stats.py): reads, unreadable, writes, refused, changes */
    uint16_t last;
    uint8_t has_last, last_mapped; /* last_mapped: the device named the address (else no text to ask) */
    uint8_t origins; /* bit t: counted of a code whose protocol table is t (FC4: input): where rehome finds its home */
    PyObject *text;       /* owned: the Python stages' text of the last value (maybe None); NULL: the namer's */
    PyObject *namer;      /* owned: the namer of the last value when text is NULL */
    PyObject *code;       /* owned, NULL: none yet */
    PyObject *code_namer; /* owned: the namer the code was last asked of */
    PyObject *status;     /* owned: the last state is this read status (`protected`...), not a value; NULL: a value */
    uint64_t order;       /* when its state was last set (Stats.states then): a merge keeps the later (rehome) */
} Param;

/* A parameter's key: by slave, address, table (profiles.register_table: input registers and holding
 * registers are tables of their own), in ParameterTable's order. */
#define PARAM_TABLES 8
static inline uint32_t param_key(int slave, int table, unsigned address) {
    return 1u << 27 | (uint32_t)slave << 19 | (address & 0xFFFF) << 3 | (uint32_t)table;
}
#define PARAM_SLAVE(key) ((key) >> 19 & 0xFF)
#define PARAM_ADDRESS(key) ((key) >> 3 & 0xFFFF)
#define PARAM_TABLE(key) ((key) & (PARAM_TABLES - 1))

/* A parameter's hash: neighbouring addresses of a slave in neighbouring slots (a read's registers touch a
 * few cache lines, not one each). */
static size_t param_hash(const void *key) {
    uint32_t k = *(const uint32_t *)key;
    return (size_t)(mix(k >> 7) + (k & 127));
}

/* (67,384 parameters of the max-size mix take 4.9 MB; open addressing of the Params took 9.4.) */
static const DenseKind PARAM_KIND = {sizeof(Param), sizeof(uint32_t), 3072, param_hash};

typedef struct {
    uint32_t fields[6], size; /* pollcycle.request_key's tuple: 2, 3, 4 or 6 fields, the others 0 */
} PollKey;

typedef struct {
    PollKey key;
    unsigned long long first, count, failed;
    Time last; /* the last occurrence's time: intervals are tallies (TALLY_INTERVALS, owner: the poll's position) */
} Poll;

static size_t poll_hash(const void *key) {
    const PollKey *k = key;
    uint64_t h = k->size;
    for (uint32_t j = 0; j < k->size; j++) h = mix(h * 0x100000001b3ULL ^ k->fields[j]);
    return (size_t)h;
}

static const DenseKind POLL_KIND = {sizeof(Poll), sizeof(PollKey), 768, poll_hash};

typedef struct {
    PyObject_HEAD
    Dense params;                 /* of Param, in the order first seen */
    Dense parts;                  /* of Param, keyed by origin for table: the parts of those two tables' codes count (_parts.h) */
    Dense polls;                  /* of Poll, in the order first seen, as PollCycle's dict keeps them */
    size_t max_keys;              /* stats_store.MAX_KEYS, given at creation */
    size_t max_params;            /* stats_store.MAX_PARAMETERS: parameters kept at most */
    uint8_t tables[256];          /* profiles.TABLES: each function code's register table */
    PyObject *device_tables;      /* stats_store.slave_tables: slave -> its device's tables (bytes), or NULL */
    PyObject *slave_tables[256];  /* owned: each slave's, asked of device_tables with the slave's namer below */
    PyObject *tables_namer[256];  /* owned: that namer (the engine's Slave gets a new one with a new device) */
    unsigned long long dropped;   /* events of parameters beyond max_params, not kept */
    unsigned long long untracked; /* requests of keys beyond max_keys */
    unsigned long long frames;    /* counted here (the engine's) */
    uint64_t states;              /* states set so far (Param.order) */
    Tallies tallies[TALLIES];     /* response times, gaps, turnarounds, load per minute, intervals, counts */
    Bus bus;                      /* bustiming.BusTiming's state (_bus.h) */
    PyObject *report;             /* a Report (_report.h) fed what is counted here too, or NULL */
} Stats;

#define PARAMS(st) ((Param *)(st)->params.items)

static int report_transaction(PyObject *report, Slave *s, const uint8_t *b, const FrameRef *qf, const FrameRef *af,
                              const Words *confirmed, const Words *reads, unsigned long long number, int table,
                              int origin);

static PyTypeObject StatsType;

/* The parameter of (slave, table, address), made on first sight; *created says so. NULL with no exception
 * set: a new parameter past max_params (a flood over every address of every slave), not kept. (A Param
 * pointer is good until the next param_get.) */
static Param *param_get(Stats *st, int slave, int table, unsigned address, int *created) {
    uint32_t key = param_key(slave, table, address);
    Param *p = dense_find(&st->params, &PARAM_KIND, &key);
    if ((*created = p == NULL) && st->params.count >= st->max_params) st->dropped++;
    else if (p == NULL) p = dense_add(&st->params, &PARAM_KIND, &key, 0);
    return p;
}

/* Is a value, or the read status `status` (a str, of an unreadable read; NULL: the value), the parameter's last
 * state? 1, 0, -1: error. */
static inline int same_state(const Param *p, unsigned value, PyObject *status) {
    if (status == NULL || p->status == NULL) return status == p->status && value == p->last;
    return PyObject_RichCompareBool(p->status, status, Py_EQ);
}

/* ParameterTable.param (render/stats_store.py, render/history.py): the state becomes a value, or the read
 * status `status`; a change is a state that differs from the last one, whoever saw each. 1: changed, -1: error. */
static inline int param_state(Param *p, unsigned value, PyObject *status) {
    int same = same_state(p, value, status);
    if (same < 0) return -1;
    int changed = p->has_last && !same;
    if (changed) p->counts[PARAM_CHANGES]++;
    Py_XSETREF(p->status, Py_XNewRef(status));
    p->last = (uint16_t)value;
    p->has_last = 1;
    return changed;
}

/* An event's count (stats_store.EVENT_RULES); 1: it sets the state too (a value or a status seen). */
static const struct { int counter, state; } event_rules[EVENTS] = EVENT_RULES;
static inline int param_sets_state(int event) { return event_rules[event].state; }
static int param_count(Param *p, int event) {
    if (event_rules[event].counter >= 0) p->counts[event_rules[event].counter]++;
    return event_rules[event].state;
}

/* namer(address, value, table): the (text, code) a slave's device gives a register of the parameter's table
 * (a map in references names input registers apart: Device.table_rows), a new reference; NULL with an
 * exception set. */
static PyObject *named(PyObject *namer, unsigned address, unsigned value, unsigned table) {
    PyObject *answer = PyObject_CallFunction(namer, "III", address, value, table);
    if (answer != NULL && (!PyTuple_Check(answer) || PyTuple_GET_SIZE(answer) != 2)) {
        Py_CLEAR(answer);
        PyErr_SetString(PyExc_TypeError, "namer must return (text, code)");
    }
    return answer;
}

/* The parameter's code as `namer` (the slave's device) gives it for (address, value), remembered with the
 * namer that gave it: 0, or -1 with an exception set. */
static int take_code(Param *p, PyObject *namer, unsigned address, unsigned value) {
    PyObject *answer = named(namer, address, value, PARAM_TABLE(p->key));
    if (answer == NULL) return -1;
    PyObject *code = PyTuple_GET_ITEM(answer, 1);
    if (code != Py_None) Py_XSETREF(p->code, Py_NewRef(code));
    Py_DECREF(answer);
    Py_XSETREF(p->code_namer, Py_NewRef(namer));
    return 0;
}

/* One event told to parameter p (`created`: just made), its state's order `order` if it sets one: its code
 * given (`code`, the Python stages'), or asked of `namer` (the slave's device, for a transaction the engine
 * shows: once per parameter and namer, only where the device names the address); CONFIRM sets it only on a
 * parameter's first sight (ParameterTable.param). An event that sets the state keeps the value, or the read
 * status `status`, and the value's text (`text`, the Python stages', or NULL: the namer's, asked when the
 * report is made). 1: the state changed, 0: not, -1: an error. (stats_store.apply_event) */
static inline __attribute__((always_inline)) int param_apply(Param *p, int created, unsigned address,
                                                              unsigned value, int event, PyObject *code,
                                                              PyObject *status, PyObject *text, PyObject *namer,
                                                              int mapped, uint64_t order) {
    if (event != EVENT_CONFIRM || created) {
        if (code != NULL && code != Py_None) Py_XSETREF(p->code, Py_NewRef(code));
        else if (code == NULL && mapped && namer != NULL && namer != Py_None && p->code_namer != namer &&
                 take_code(p, namer, address, value) < 0)
            return -1;
    }
    if (!param_count(p, event)) return 0;
    int changed = param_state(p, value, status);
    p->order = order;
    if (changed < 0 || status != NULL) return changed;
    p->last_mapped = (uint8_t)mapped;
    Py_XSETREF(p->text, Py_XNewRef(text));
    if (p->namer != namer) Py_XSETREF(p->namer, Py_XNewRef(namer));
    return changed;
}

/* The objects a parameter holds released, each once (the store's end, a merge, a failed rehome). */
static void param_release(Param *p) {
    CLEAR_ALL(&p->text, &p->namer, &p->code, &p->code_namer, &p->status);
}

#include "_parts.h" /* a parameter two protocol tables' codes count: their parts, the moves of a new device */

/* One register's event (param_apply) to the parameter of (slave, table, address) (made on first sight), and
 * to its origin's part where codes of two protocol tables count it (part_event). 1: the state changed, 0: not
 * (or not kept), -1: an error. (Inlined: in words_event, once per register, the constant arguments fold away.) */
static inline __attribute__((always_inline)) int param_event(Stats *st, int slave, int table, int origin,
                                                              unsigned address, unsigned value, int event,
                                                              PyObject *code, PyObject *status, PyObject *text,
                                                              PyObject *namer, int mapped) {
    int created;
    Param *p = param_get(st, slave, table, address, &created);
    if (p == NULL) return PyErr_Occurred() ? -1 : 0;
    uint8_t bit = (uint8_t)(1u << origin);
    if ((p->origins | bit) != bit &&
        part_event(st, p, slave, origin, address, value, event, code, status, text, namer, mapped) < 0)
        return -1;
    p->origins |= bit;
    int changed = param_apply(p, created, address, value, event, code, status, text, namer, mapped, st->states + 1);
    if (changed >= 0 && param_sets_state(event)) st->states++;
    return changed;
}

/* Register tables by byte (profiles.TABLES, stats_store.slave_tables' and SlaveTables' bytes), `what` gave
 * them: 0, or -1 with ValueError when one is past the PARAM_TABLES a key holds. */
static int tables_valid(const char *tables, Py_ssize_t size, const char *what) {
    for (Py_ssize_t k = 0; k < size; k++)
        if ((uint8_t)tables[k] >= PARAM_TABLES) {
            PyErr_Format(PyExc_ValueError, "%s: 0..%d each", what, PARAM_TABLES - 1);
            return -1;
        }
    return 0;
}

/* The table of a code's registers on the slave's device (Stats.device_tables; else the protocol's), asked
 * again when the slave's namer is another (its device changed: profile `auto`); -1: an error. */
static int slave_table(Stats *st, Slave *s, int slave, int function) {
    if (st->device_tables == NULL) return st->tables[function];
    if (st->slave_tables[slave] == NULL || st->tables_namer[slave] != s->namer) {
        PyObject *tables = PyObject_CallFunction(st->device_tables, "i", slave);
        if (tables == NULL) return -1;
        if (!PyBytes_Check(tables) || PyBytes_GET_SIZE(tables) != 256 ||
            tables_valid(PyBytes_AS_STRING(tables), 256, "device tables") < 0) {
            if (!PyErr_Occurred()) PyErr_SetString(PyExc_TypeError, "device tables: 256 bytes, a table each code");
            Py_DECREF(tables);
            return -1;
        }
        Py_XSETREF(st->slave_tables[slave], tables);
        Py_XSETREF(st->tables_namer[slave], Py_XNewRef(s->namer));
    }
    return (uint8_t)PyBytes_AS_STRING(st->slave_tables[slave])[function];
}

static int words_event(Stats *st, Slave *s, int slave, int table, int origin, const Words *w, int event) {
    for (unsigned k = 0; k < w->count; k++) {
        unsigned address = words_address(w, k);
        int mapped = bit(s->mapped, address);
        if (param_event(st, slave, table, origin, address, words_value(w, k), event, NULL, NULL, NULL, s->namer,
                        mapped) < 0)
            return -1;
    }
    return 0;
}

/* ---- poll keys: pollcycle.request_key ---------------------------------------------------------- */
/* PollCycle.add_request: 0 or -1 (no memory). */
static int poll_request(Stats *st, const PollKey *key, unsigned long long number, int failed, const Time *t) {
    Poll *p = dense_find(&st->polls, &POLL_KIND, key);
    if (p == NULL && st->polls.count >= st->max_keys) {
        st->untracked++;
        return 0;
    }
    if (p == NULL) {
        if ((p = dense_add(&st->polls, &POLL_KIND, key, 0)) == NULL) return -1;
        p->first = number;
    }
    p->count++;
    if (failed) p->failed++;
    if (!t->has) return 0;
    long long order = p - (Poll *)st->polls.items;
    double interval = p->last.has ? time_sub(t, &p->last) : -1.0; /* (time going backwards: none) */
    if (interval >= 0 && tally_add(st->tallies, TALLY_INTERVALS, order, (long long)rint(interval / POLL_STEP), 1) < 0)
        return -1;
    p->last = *t;
    return 0;
}

/* PollCycle.add_answer: an exception (or a damaged answer) to a request: that cycle missed. */
static void poll_fail(Stats *st, const PollKey *key) {
    Poll *p = dense_find(&st->polls, &POLL_KIND, key);
    if (p != NULL) p->failed++;
}

/* pollcycle.request_key of a request the engine shows: its window and the window it writes (FC23) as lift_frame
 * read them by the protocol table's request layout; FC8 by its sub-function, the data's first word; FC43 by its
 * MEI type, and 14's by its read code and object id (a basic and an extended identification: two polls). */
static void request_key(const uint8_t *f, const Lifted *r, PollKey *key) {
    const Lift *L = &request_lift[handled_index(f[1])];
    uint32_t fields[6] = {f[0], f[1], L->special ? word(f + 2) : r->start, r->quantity, r->values.start, r->values.count};
    *key = (PollKey){{0}, L->special ? 3 : !L->start_at ? 2 : L->write_quantity_at ? 6 : 4}; /* (the others 0) */
    if (f[1] == MEI_FUNCTION && r->length >= 5) { /* (its MEI type there: slave, code, type, CRC) */
        int device_id = f[2] == MEI_DEVICE_ID && r->length >= 7;
        fields[2] = f[2], fields[3] = f[3], fields[4] = f[4];
        key->size = device_id ? 5 : f[2] == MEI_DEVICE_ID ? 2 : 3;
    }
    memcpy(key->fields, fields, key->size * sizeof *fields);
}

/* What StatsCollector.add and BusTiming.add do with a transaction the engine shows: the request (unanswered
 * when `af` is NULL; as lifted: `request`, its registers written: FC6, 16, 23), then its normal answer or
 * exception. `reads`: the answer's values (FC3, 4, 23); `base`: the stream offset of b[0]. */
static int count_transaction(Stats *st, Slave *s, const uint8_t *b, const FrameRef *qf, const FrameRef *af,
                             const Lifted *request, const Words *reads, unsigned long long number, long long base) {
    const uint8_t *q = b + qf->at, *answer = af != NULL ? b + af->at : NULL;
    const Words *writes = request->values.values != NULL ? &request->values : NULL;
    int slave = q[0], function = q[1];
    Words written; /* the writes a normal answer confirms (data/modbus.toml [confirm]): counted and drawn */
    const Words *confirmed =
        answer != NULL && !(answer[1] & 0x80) && confirmed_writes(answer, writes, &written) ? &written : NULL;
    int table = slave_table(st, s, slave, function), origin = st->tables[function];
    /* A mask write of a slave that follows no memory (frame_is_quiet): a write of its register (counted as 0
     * where and_mask is not 0), its echo confirming (old AND and_mask) OR (or_mask AND NOT and_mask), old the
     * parameter's last value; nothing where that is not known (history.History._mask, memory.masked_value) */
    static const uint8_t unknown[2];
    unsigned and_mask = word(q + 4), known = !and_mask;
    uint8_t result[2];
    Words mask = {word(q + 2), 1, and_mask ? unknown : q + 6}, masked = {word(q + 2), 1, result};
    if (rules[handled_index(function)].confirm == CONFIRM_MASK) {
        uint32_t key = param_key(slave, table < 0 ? 0 : table, word(q + 2));
        const Param *p = table < 0 ? NULL : dense_find(&st->params, &PARAM_KIND, &key);
        unsigned old = p != NULL && p->has_last && p->status == NULL ? (known = 1, p->last) : 0;
        unsigned value = (old & and_mask) | (word(q + 6) & ~and_mask & 0xFFFF);
        result[0] = (uint8_t)(value >> 8), result[1] = (uint8_t)value;
        writes = &mask, confirmed = answer != NULL && !(answer[1] & 0x80) && known ? &masked : NULL;
    }
    if (table < 0 || (st->report != NULL && report_transaction(st->report, s, b, qf, af, confirmed, reads, number,
                                                                  table, origin) < 0))
        return -1;
    Time qt = stamp_time(qf->timed, qf->ns);
    stats_seen(&st->bus, &qt);
    if (bus_add(st->tallies, &st->bus, &qt, qf->length, frame_sent(qf, st->bus.char_time), KIND_REQUEST, slave, 0,
                af == NULL, 1, NULL, number, base + qf->at) < 0)
        return -1;
    if (af != NULL) {
        Time at = stamp_time(af->timed, af->ns);
        double response = stamp_seconds(af->ns, qf->ns);
        int timed = qf->timed && af->timed;
        stats_seen(&st->bus, &at);
        if (bus_add(st->tallies, &st->bus, &at, af->length, frame_sent(af, st->bus.char_time), af->kind, slave, 0, 0,
                    1, timed ? &response : NULL, number + 1, base + af->at) < 0)
            return -1;
        if (timed && tally_add(st->tallies, TALLY_TIMES, slave << 8 | function, (long long)rint(response * 1e9), 1) < 0)
            return -1;
    }
    PollKey key;
    request_key(q, request, &key);
    int owner = slave << 8 | function;
    st->frames += answer != NULL ? 2 : 1;
    if (tally_add(st->tallies, TALLY_COUNTS, owner, COUNT_REQUESTS, 1) < 0 ||
        (answer == NULL && tally_add(st->tallies, TALLY_COUNTS, owner, COUNT_UNANSWERED, 1) < 0) ||
        poll_request(st, &key, number, answer == NULL, &qt) < 0)
        return -1;
    if (writes != NULL && words_event(st, s, slave, table, origin, writes, EVENT_WRITE) < 0) return -1;
    if (answer == NULL) return 0;
    if (answer[1] & 0x80) { /* an exception: counted by its code */
        if (tally_add(st->tallies, TALLY_COUNTS, owner, answer[2], 1) < 0) return -1;
        poll_fail(st, &key);
        return writes != NULL ? words_event(st, s, slave, table, origin, writes, EVENT_REFUSED) : 0;
    }
    if (tally_add(st->tallies, TALLY_COUNTS, owner, COUNT_RESPONSES, 1) < 0) return -1;
    if (confirmed != NULL && words_event(st, s, slave, table, origin, confirmed, EVENT_CONFIRM) < 0) return -1;
    return reads != NULL && reads->count ? words_event(st, s, slave, table, origin, reads, EVENT_READ) : 0;
}

/* ---- the Python object ------------------------------------------------------------------------- */
static void stats_dealloc(Stats *st) {
    for (size_t k = 0; k < st->params.count; k++) param_release(&PARAMS(st)[k]);
    for (size_t k = 0; k < st->parts.count; k++) param_release(&((Param *)st->parts.items)[k]);
    CLEAR_ALL(&st->report, &st->device_tables);
    for (int k = 0; k < 256; k++) CLEAR_ALL(&st->slave_tables[k], &st->tables_namer[k]);
    dense_free(&st->params);
    dense_free(&st->parts);
    dense_free(&st->polls);
    for (int k = 0; k < TALLIES; k++) dense_free(&st->tallies[k].d);
    PyMem_Free(st->bus.outages);
    Py_TYPE(st)->tp_free((PyObject *)st);
}

/* param(slave, address, event, value, code, text, table=0, origin=None): a register of a frame the Python stages
 * showed; `origin`: its code's table in the protocol (None: `table`). */
static PyObject *stats_param(Stats *st, PyObject *args) {
    int slave, event, table = 0;
    unsigned address, value;
    PyObject *code, *text, *given = Py_None;
    if (!PyArg_ParseTuple(args, "iIiIOO|iO", &slave, &address, &event, &value, &code, &text, &table, &given))
        return NULL;
    long origin = given == Py_None ? table : PyLong_Check(given) ? PyLong_AsLong(given) : -1;
    if (slave < 0 || slave > 255 || address > 0xFFFF || event < 0 || event >= EVENTS || value > 0xFFFF ||
        table < 0 || table >= PARAM_TABLES || origin < 0 || origin >= PARAM_TABLES) {
        PyErr_Clear();
        return PyErr_Format(PyExc_ValueError, "param: slave 0..255, address and value 0..65535, a known event, "
                                              "table and origin 0..7");
    }
    if (event == EVENT_UNREADABLE && !PyUnicode_Check(text))
        return PyErr_Format(PyExc_TypeError, "param: an UNREADABLE event's text is its status");
    /* UNREADABLE (16#8000 or an explained exception): `text` is the status, no value */
    int unreadable = event == EVENT_UNREADABLE;
    int changed = param_event(st, slave, table, (int)origin, address, value, event, code, unreadable ? text : NULL,
                              unreadable ? NULL : text, NULL, 0);
    return changed < 0 ? NULL : PyBool_FromLong(changed);
}

/* rename({slave: namer}): the values kept of these slaves were read before their profile was chosen:
 * name them (text and code) as the chosen device does, once (render/history.py, a profile change). */
static PyObject *stats_rename(Stats *st, PyObject *namers) {
    if (!PyDict_Check(namers)) return PyErr_Format(PyExc_TypeError, "rename: a dict {slave: namer}");
    for (size_t k = 0; k < st->params.count; k++) {
        Param *p = &PARAMS(st)[k];
        PyObject *slave = PyLong_FromUnsignedLong(PARAM_SLAVE(p->key));
        if (slave == NULL) return NULL;
        PyObject *namer = PyDict_GetItemWithError(namers, slave);
        Py_DECREF(slave);
        if (namer == NULL) {
            if (PyErr_Occurred()) return NULL;
            continue;
        }
        Py_CLEAR(p->code); /* the new device's code, none where it names nothing (not the old one's) */
        if (take_code(p, namer, PARAM_ADDRESS(p->key), p->status ? 0u : (unsigned)p->last) < 0) return NULL;
        Py_XSETREF(p->namer, Py_NewRef(namer));
        Py_CLEAR(p->text);
        p->last_mapped = 1;
    }
    Py_RETURN_NONE;
}

/* A request key tuple (slave, function[, ...]) of up to 6 ints into *fields: 0 or -1. */
static int key_fields(PyObject *key, PollKey *fields) {
    if (!PyTuple_Check(key) || PyTuple_GET_SIZE(key) < 2 || PyTuple_GET_SIZE(key) > 6)
        return fail(PyExc_TypeError, "a request key: a tuple of 2 to 6 ints");
    *fields = (PollKey){.size = (uint32_t)PyTuple_GET_SIZE(key)};
    for (uint32_t k = 0; k < fields->size; k++) {
        unsigned long v = PyLong_AsUnsignedLong(PyTuple_GET_ITEM(key, k));
        if (v == (unsigned long)-1 && PyErr_Occurred()) return -1;
        if (v > 0xFFFFFFFFUL) return fail(PyExc_ValueError, "a request key's fields are 32-bit");
        fields->fields[k] = (uint32_t)v;
    }
    return 0;
}

static PyObject *stats_poll(Stats *st, PyObject *args) {
    PyObject *key, *time = Py_None;
    unsigned long long number;
    int failed;
    if (!PyArg_ParseTuple(args, "OKp|O", &key, &number, &failed, &time)) return NULL;
    PollKey fields;
    Time t;
    if (key_fields(key, &fields) < 0 || read_time(time, &t) < 0 || poll_request(st, &fields, number, failed, &t) < 0)
        return NULL;
    Py_RETURN_NONE;
}

static PyObject *stats_poll_fail(Stats *st, PyObject *key) {
    PollKey fields;
    if (key_fields(key, &fields) < 0) return NULL;
    poll_fail(st, &fields);
    Py_RETURN_NONE;
}

static int param_order(const void *a, const void *b) {
    uint32_t x = (*(Param *const *)a)->key, y = (*(Param *const *)b)->key;
    return x < y ? -1 : x > y;
}

/* The last value's text: the Python stages' (maybe None), else the namer's where the device names
 * the address; None for no text. A new reference. */
static PyObject *param_text(const Param *p) {
    if (p->status != NULL) return Py_NewRef(p->status);
    if (p->text != NULL) return Py_NewRef(p->text);
    if (!p->has_last || !p->last_mapped || p->namer == NULL || p->namer == Py_None) Py_RETURN_NONE;
    PyObject *answer = named(p->namer, PARAM_ADDRESS(p->key), (unsigned)p->last, PARAM_TABLE(p->key));
    if (answer == NULL) return NULL;
    PyObject *text = Py_NewRef(PyTuple_GET_ITEM(answer, 0));
    Py_DECREF(answer);
    return text;
}

/* (slave, address, code, reads, unreadable, writes, refused, last, last_text, changes, table), built item by
 * item (Py_BuildValue's format parsing was a third of the cost); last_text the text of the last value,
 * None when nothing names it; when the last state is a read status, last is None and last_text the status. */
static PyObject *param_row(const Param *p) {
    PyObject *row = PyTuple_New(11), *text = row != NULL ? param_text(p) : NULL;
    if (text == NULL) {
        Py_XDECREF(row);
        return NULL;
    }
    PyObject *code = Py_NewRef(p->code ? p->code : Py_None);
    PyObject *last = p->has_last && p->status == NULL ? PyLong_FromUnsignedLong(p->last) : Py_NewRef(Py_None);
    const uint32_t *n = p->counts;
    const unsigned long fields[] = {PARAM_SLAVE(p->key), PARAM_ADDRESS(p->key), 0, n[PARAM_READS], n[PARAM_UNREADABLE],
                                    n[PARAM_WRITES], n[PARAM_REFUSED], 0, 0, n[PARAM_CHANGES], PARAM_TABLE(p->key)};
    for (int j = 0; j < 11; j++)
        PyTuple_SET_ITEM(row, j, j == 2 ? code : j == 7 ? last : j == 8 ? text : PyLong_FromUnsignedLong(fields[j]));
    for (int j = 0; j < 11; j++)
        if (PyTuple_GET_ITEM(row, j) == NULL) { /* no memory for an int */
            Py_DECREF(row);
            return NULL;
        }
    return row;
}

/* b follows a in --stats' parameter table's run: the next address of the slave's table, the same counts, both
 * named or both not (render/stats.py _parameter_table). */
static int same_story(const Param *a, const Param *b) {
    return b->key == a->key + 8 && PARAM_ADDRESS(a->key) != 0xFFFF && memcmp(b->counts, a->counts, sizeof a->counts) == 0 &&
           (b->code == NULL) == (a->code == NULL);
}

/* table(max_rows, group_min) -> (pieces, expanded, count, (reads, unreadable, writes, refused, changes)):
 * stats_store.ParameterTable.table, the rows of the parameter table without a row per parameter. */
static PyObject *stats_table(Stats *st, PyObject *args) {
    Py_ssize_t max_rows, group_min;
    if (!PyArg_ParseTuple(args, "nn", &max_rows, &group_min)) return NULL;
    size_t n = st->params.count, first = 0;
    Param **order = PyMem_Malloc((n ? n : 1) * sizeof *order); /* the parameters by (slave, address) */
    for (size_t k = 0; order != NULL && k < n; k++) order[k] = &PARAMS(st)[k];
    if (order != NULL) qsort(order, n, sizeof *order, param_order);
    PyObject *pieces = order != NULL ? PyList_New(0) : PyErr_NoMemory();
    unsigned long long totals[PARAM_COUNTS] = {0}, expanded = 0;
    for (size_t k = 0; pieces != NULL && k < n; k++) {
        const Param *p = order[k];
        for (int j = 0; j < PARAM_COUNTS; j++) totals[j] += p->counts[j];
        if (k + 1 < n && same_story(p, order[k + 1])) continue;
        size_t end = k + 1;
        int grouped = end - first >= (size_t)group_min;
        for (size_t start = first; start < end && PyList_GET_SIZE(pieces) < max_rows; start = grouped ? end : start + 1) {
            size_t stop = grouped ? end : start + 1;
            PyObject *members = PyList_New(0);
            for (size_t m = start; members != NULL && m < stop; m++)
                if (list_put(members, param_row(order[m])) < 0) Py_CLEAR(members);
            if (list_put(pieces, members) < 0) {
                Py_CLEAR(pieces);
                break;
            }
        }
        expanded += grouped ? 1 : end - first;
        first = end;
    }
    PyMem_Free(order);
    if (pieces == NULL) return NULL;
    return Py_BuildValue("(NKn(KKKKK))", pieces, expanded, (Py_ssize_t)n, totals[0], totals[1], totals[2], totals[3],
                         totals[4]);
}

/* The parameter writes() and last() are asked of, (slave, address, table=0): 0 with *found it (NULL: not seen, not
 * kept), -1 with an error. ("b": a slave past 0..255 is an OverflowError; "H" keeps an address's 16 bits.) */
static int asked_param(Stats *st, PyObject *args, const char *what, const Param **found) {
    unsigned char slave, table = 0;
    unsigned short address;
    if (!PyArg_ParseTuple(args, "bH|b", &slave, &address, &table)) return -1;
    if (table >= PARAM_TABLES) {
        PyErr_Format(PyExc_ValueError, "%s: table 0..7", what);
        return -1;
    }
    uint32_t key = param_key(slave, table, address);
    *found = dense_find(&st->params, &PARAM_KIND, &key);
    return 0;
}

/* writes(slave, address, table=0) -> the writes counted of that parameter (0: none, or not kept): the report's
 * setpoints (report/html.py). */
static PyObject *stats_writes(Stats *st, PyObject *args) {
    const Param *p;
    if (asked_param(st, args, "writes", &p) < 0) return NULL;
    return PyLong_FromUnsignedLong(p != NULL ? p->counts[PARAM_WRITES] : 0);
}

/* last(slave, address, table=0) -> the parameter's last value; None where its state is a read status, or none
 * (not seen, not kept): a mask write's old value (history.History._mask). */
static PyObject *stats_last(Stats *st, PyObject *args) {
    const Param *p;
    if (asked_param(st, args, "last", &p) < 0) return NULL;
    if (p == NULL || !p->has_last || p->status != NULL) Py_RETURN_NONE;
    return PyLong_FromUnsignedLong(p->last);
}

/* polls() -> [(key, first frame, count, failed)] in the order the keys were first seen */
static PyObject *stats_polls(Stats *st, PyObject *unused) {
    PyObject *rows = PyList_New((Py_ssize_t)st->polls.count);
    for (size_t k = 0; rows != NULL && k < st->polls.count; k++) {
        const Poll *p = (const Poll *)st->polls.items + k;
        PyObject *key = PyTuple_New(p->key.size), *row = NULL;
        for (uint32_t j = 0; key != NULL && j < p->key.size; j++) {
            PyObject *v = PyLong_FromUnsignedLong(p->key.fields[j]);
            if (v == NULL) Py_CLEAR(key);
            else PyTuple_SET_ITEM(key, j, v);
        }
        if (key == NULL || (row = Py_BuildValue("(NKKK)", key, p->first, p->count, p->failed)) == NULL) Py_CLEAR(rows);
        else PyList_SET_ITEM(rows, (Py_ssize_t)k, row);
    }
    return rows;
}

/* bus_line(char_time, t35, timeout, new_input): the line's settings (BusTiming.char_time, t35, timeout);
 * new_input: a new file, whose gaps do not continue the previous one's (BusTiming.new_input). */
static PyObject *stats_bus_line(Stats *st, PyObject *args) {
    int fresh;
    if (!PyArg_ParseTuple(args, "dddp", &st->bus.char_time, &st->bus.t35, &st->bus.timeout, &fresh)) return NULL;
    if (fresh) {
        st->bus.has_last_end = st->bus.has_answer_end = 0;
        st->bus.input++;
    }
    Py_RETURN_NONE;
}

/* bus_item(time, length, sent, kind, slave, broadcast, unanswered, crc_ok, response_time, number, offset):
 * BusTiming.add of an item the Python stages showed (kind: 0 noise, 1 request, 2 response, 3 exception; sent:
 * model.sent_in at the bus's character time). */
static PyObject *stats_bus_item(Stats *st, PyObject *args) {
    PyObject *time, *response;
    long long length, offset;
    double sent;
    int kind, slave, broadcast, unanswered, crc_ok;
    unsigned long long number;
    if (!PyArg_ParseTuple(args, "OLdiippiOKL", &time, &length, &sent, &kind, &slave, &broadcast, &unanswered,
                          &crc_ok, &response, &number, &offset))
        return NULL;
    Time t;
    double seconds = 0.0;
    if (read_time(time, &t) < 0) return NULL;
    if (response != Py_None && (seconds = PyFloat_AsDouble(response)) == -1.0 && PyErr_Occurred()) return NULL;
    if (slave < 0 || slave > 255 || kind < 0 || kind > KIND_EXCEPTION)
        return PyErr_Format(PyExc_ValueError, "bus_item: slave 0..255, kind 0..3");
    if (bus_add(st->tallies, &st->bus, &t, length, sent, kind, slave, broadcast, unanswered, crc_ok,
                response != Py_None ? &seconds : NULL, number, offset) < 0)
        return NULL;
    Py_RETURN_NONE;
}

/* stamp(time): StatsCollector.add's first and last times, of an item the Python stages showed. */
static PyObject *stats_stamp(Stats *st, PyObject *time) {
    Time t;
    if (read_time(time, &t) < 0) return NULL;
    stats_seen(&st->bus, &t);
    Py_RETURN_NONE;
}

static PyObject *runs_value(const Run *runs, size_t count, int active_only) {
    PyObject *rows = PyList_New(0);
    for (size_t k = 0; rows != NULL && k < count; k++) {
        const Run *r = &runs[k];
        if (active_only && !r->active) continue;
        PyObject *row = Py_BuildValue("(iNNKKKLII)", r->slave, time_value(&r->start), time_value(&r->end),
                                      r->requests, r->first_frame, r->last_frame, r->offset, r->first_input,
                                      r->last_input);
        if (list_put(rows, row) < 0) Py_CLEAR(rows);
    }
    return rows;
}

static PyObject *quantile_value(const Quantile *q) { return Py_BuildValue("(dd)", q->low, q->high); }

/* response(slave, function, ns): a response time of an answer the Python stages showed (StatsCollector.add);
 * slave and function 0..255 ("b": OverflowError past them). */
static PyObject *stats_response(Stats *st, PyObject *args) {
    unsigned char slave, function;
    long long ns;
    if (!PyArg_ParseTuple(args, "bbL", &slave, &function, &ns)) return NULL;
    if (tally_add(st->tallies, TALLY_TIMES, slave << 8 | function, ns, 1) < 0) return NULL;
    Py_RETURN_NONE;
}

static int tally_order(const void *a, const void *b) {
    const Tally *x = a, *y = b;
    if (x->tag != y->tag) return x->tag < y->tag ? -1 : 1;
    return x->key < y->key ? -1 : x->key > y->key;
}

/* tallies(kind) -> {owner: {key: count}} of one histogram (_bus.h TALLY_*), by owner and key (sorted here); sums
 * (TALLY_MINUTES) as floats. What render/stats.py, pollcycle.py and report/html.py work out of them, they do. */
static PyObject *stats_tallies(Stats *st, PyObject *arg) {
    int kind;
    if (!PyArg_Parse(arg, "i", &kind)) return NULL;
    if (kind < 0 || kind >= TALLIES) return PyErr_Format(PyExc_ValueError, "tallies: an unknown kind");
    const Tallies *table = &st->tallies[kind];
    size_t n = table->d.count;
    Tally *all = PyMem_Malloc((n ? n : 1) * sizeof *all);
    if (all == NULL) return PyErr_NoMemory();
    memcpy(all, table->d.items, n * sizeof *all);
    qsort(all, n, sizeof *all, tally_order);
    PyObject *groups = PyDict_New(), *dict = NULL;
    for (size_t k = 0; groups != NULL && k < n; k++) {
        if (k == 0 || all[k].tag != all[k - 1].tag) {
            dict = PyDict_New();
            if (dict_put(groups, PyLong_FromUnsignedLong(all[k].tag & 0xFFFFFF), dict) < 0) {
                Py_CLEAR(groups);
                break;
            }
        }
        PyObject *count = kind == TALLY_MINUTES ? PyFloat_FromDouble(all[k].value) : PyLong_FromDouble(all[k].value);
        if (dict_put(dict, PyLong_FromLongLong(all[k].key), count) < 0) Py_CLEAR(groups);
    }
    PyMem_Free(all);
    return groups;
}

/* bus_state(): what BusTiming keeps but its histograms (tallies()), for the report (bustiming.py). */
static PyObject *stats_bus_state(Stats *st, PyObject *unused) {
    const Bus *b = &st->bus;
    PyObject *histogram = PyList_New(0), *responses = PyList_New(0);
    for (size_t k = 0; histogram != NULL && k < GAP_BINS; k++)
        if (list_put(histogram, PyLong_FromUnsignedLongLong(b->histogram[k])) < 0) Py_CLEAR(histogram);
    for (int slave = 0; responses != NULL && slave < 256; slave++) {
        const Quantile *q = &b->responses[slave];
        if (q->low <= q->high &&
            list_put(responses, Py_BuildValue("(iddKd)", slave, q->low, q->high, b->close[slave], b->waits[slave])) < 0)
            Py_CLEAR(responses); /* (low > high: no response time; waits: _bus.h) */
    }
    /* (Py_BuildValue releases its N arguments when one of them is NULL) */
    PyObject *last_end = b->has_last_end ? PyFloat_FromDouble(b->last_end) : Py_NewRef(Py_None);
    PyObject *answer_end = b->has_answer_end ? PyFloat_FromDouble(b->answer_end) : Py_NewRef(Py_None);
    return Py_BuildValue("{s:O,s:K,s:N,s:N,s:d,s:N,s:K,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:K,s:N,s:N,s:d,s:d,s:K}", "timed",
                         b->timed ? Py_True : Py_False, "untimed", b->untimed, "first", time_value(&b->first),
                         "last_end", last_end, "busy", b->busy, "answer_end", answer_end, "below_t35", b->below_t35,
                         "histogram", histogram, "gaps", quantile_value(&b->gaps), "turnaround",
                         quantile_value(&b->turnaround), "responses", responses, "runs",
                         runs_value(b->runs, 256, 1), "outages", runs_value(b->outages, b->outage_count, 0), "first_seen",
                         time_value(&b->first_seen), "last_seen", time_value(&b->last_seen), "backwards", b->backwards,
                         "previous", time_value(&b->previous), "stretch", time_value(&b->stretch), "reach", b->reach,
                         "spanned", b->spanned, "same_stamp_overlaps", b->same_stamp_overlaps);
}

/* Stats(max_keys, max_params=MAX_PARAMETERS, max_tally=MAX_TALLY, tables=b"", device_tables=None): the poll
 * table follows at
 * most max_keys request keys (stats_store.MAX_KEYS), the parameter table keeps at most max_params parameters
 * (MAX_PARAMETERS), each kind of histogram but the load per minute at most max_tally entries (MAX_TALLY,
 * _bus.h Tallies); `tables`: each function code's register table (profiles.TABLES; missing: 0);
 * `device_tables`: slave -> its device's tables instead (stats_store.slave_tables), None: `tables`. */
static int stats_init(Stats *st, PyObject *args, PyObject *kwargs) {
    static char *keywords[] = {"max_keys", "max_params", "max_tally", "tables", "device_tables", NULL};
    Py_ssize_t max_keys, max_params = MAX_PARAMETERS, max_tally = MAX_TALLY, size = 0;
    const char *tables = "";
    PyObject *device_tables = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "n|nny#O", keywords, &max_keys, &max_params, &max_tally, &tables,
                                     &size, &device_tables))
        return -1;
    if (device_tables != Py_None && !PyCallable_Check(device_tables))
        return fail(PyExc_TypeError, "device_tables: slave -> bytes, or None");
    Py_XSETREF(st->device_tables, device_tables == Py_None ? NULL : Py_NewRef(device_tables));
    if (max_keys < 0 || max_params < 0 || max_tally < 0 || size > 256)
        return fail(PyExc_ValueError, "max_keys, max_params and max_tally must be >= 0, tables 256 at most");
    if (tables_valid(tables, size, "tables") < 0) return -1;
    memset(st->tables, 0, sizeof st->tables);
    memcpy(st->tables, tables, (size_t)size);
    st->max_keys = (size_t)max_keys;
    st->max_params = (size_t)max_params;
    for (int k = 0; k < TALLIES; k++) st->tallies[k].limit = TALLY_UNBOUNDED >> k & 1 ? 0 : (size_t)max_tally;
    bus_init(&st->bus);
    return 0;
}

static PyMethodDef stats_methods[] = {
    {"param", (PyCFunction)stats_param, METH_VARARGS,
     "param(slave, address, event, value, code, text, table=0): a register of a frame the Python stages showed\n"
     "(event: stats_store.EVENTS' index; UNREADABLE's text is the status); True when the state changed."},
    {"rename", (PyCFunction)stats_rename, METH_O,
     "rename({slave: namer}): name the kept values of these slaves as their new profile does."},
    {"rehome", (PyCFunction)stats_rehome, METH_VARARGS,
     "rehome(slave, homes): move the slave's parameters to the tables homes (bytes by table) gives their codes' tables"},
    {"poll", (PyCFunction)stats_poll, METH_VARARGS, "poll(key, frame number, failed, time=None): a good request."},
    {"poll_fail", (PyCFunction)stats_poll_fail, METH_O, "poll_fail(key): its answer was an exception."},
    {"bus_line", (PyCFunction)stats_bus_line, METH_VARARGS, "bus_line(char_time, t35, timeout, new_input)"},
    {"bus_item", (PyCFunction)stats_bus_item, METH_VARARGS,
     "bus_item(time, length, sent, kind, slave, broadcast, unanswered, crc_ok, response_time, number, offset)"},
    {"stamp", (PyCFunction)stats_stamp, METH_O, "stamp(time): an item's time (first and last seen)"},
    {"response", (PyCFunction)stats_response, METH_VARARGS, "response(slave, function, ns): a response time"},
    {"tallies", (PyCFunction)stats_tallies, METH_O, "tallies(kind) -> {owner: {key: count}}: a histogram"},
    {"bus_state", (PyCFunction)stats_bus_state, METH_NOARGS, "BusTiming's state but its histograms"},
    {"table", (PyCFunction)stats_table, METH_VARARGS,
     "table(max_rows, group_min) -> (pieces, expanded, count, totals): the --stats parameter table's rows"},
    {"polls", (PyCFunction)stats_polls, METH_NOARGS, "[(key, first frame, count, failed)]"},
    {"last", (PyCFunction)stats_last, METH_VARARGS, "last(slave, address, table=0) -> its last value, or None"},
    {"writes", (PyCFunction)stats_writes, METH_VARARGS,
     "writes(slave, address, table=0): the writes counted of a parameter"},
    {NULL, NULL, 0, NULL},
};

static int stats_set_report(Stats *st, PyObject *value, void *closure);

static PyGetSetDef stats_getset[] = {
    {"report", (getter)object_get, (setter)stats_set_report, "a Report fed what is counted here, or None",
     (void *)offsetof(Stats, report)},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyMemberDef stats_members[] = {
    {"frames", T_ULONGLONG, offsetof(Stats, frames), READONLY, "frames the engine counted"},
    {"untracked", T_ULONGLONG, offsetof(Stats, untracked), READONLY, "requests of keys beyond the poll table's size"},
    {"parameter_count", T_PYSSIZET, offsetof(Stats, params.count), READONLY, "parameters kept"},
    {"dropped", T_ULONGLONG, offsetof(Stats, dropped), READONLY, "events of parameters beyond max_params, not kept"},
    {NULL, 0, 0, 0, NULL},
};

static PyTypeObject StatsType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "dissector.accel._summary.Stats",
    .tp_basicsize = sizeof(Stats),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "--stats counts kept in C (see render/stats.py, EngineStore).",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)stats_init,
    .tp_dealloc = (destructor)stats_dealloc,
    .tp_methods = stats_methods,
    .tp_getset = stats_getset,
    .tp_members = stats_members,
};
