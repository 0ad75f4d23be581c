/* --stats' time-dependent counts in the engine, for timed captures (pcap, pcapng) and the raw ones alike:
 * what render/bustiming.py BusTiming.add, render/pollcycle.py's intervals and StatsCollector's response
 * times and first and last times do per item. Once a collector is attached (StatsCollector.engine_store),
 * these live here for the rest of the run and the Python stages send their own items here too
 * (Stats.bus_item, Stats.stamp, Stats.poll with a time), so that gaps, turnarounds, outages and
 * intervals follow the stream's order whichever side saw each frame; the Python objects take the
 * state back when the report is made (Stats.bus_state, Stats.tallies). Included by _stats.h.
 *
 * Times are kept as the Python stages have them: a float, and the source's integer nanoseconds where
 * it is a model.Stamp (two stamps subtract exactly, anything else as floats do). */
typedef struct {
    int has, exact;
    long long ns;
    double d;
} Time;

static inline Time stamp_time(int timed, long long ns) {
    Time t = {timed, 1, ns, timed ? stamp_seconds(ns, 0) : 0.0};
    return t;
}

/* a - b as the Python stages subtract them: Stamp - Stamp exactly, else as floats. */
static inline double time_sub(const Time *a, const Time *b) {
    return a->exact && b->exact ? stamp_seconds(a->ns, b->ns) : a->d - b->d;
}

/* A Python time (None, a float or a model.Stamp) into *t: 0, or -1 with an exception set. */
static int read_time(PyObject *value, Time *t) {
    memset(t, 0, sizeof *t);
    if (value == Py_None) return 0;
    t->has = 1;
    t->d = PyFloat_AsDouble(value);
    if (t->d == -1.0 && PyErr_Occurred()) return -1;
    PyObject *ns = PyObject_GetAttrString(value, "ns");
    if (ns == NULL) {
        if (!PyErr_ExceptionMatches(PyExc_AttributeError)) return -1;
        PyErr_Clear();
        return 0;
    }
    int overflow;
    t->ns = PyLong_AsLongLongAndOverflow(ns, &overflow);
    Py_DECREF(ns);
    if (t->ns == -1 && PyErr_Occurred()) return -1;
    /* Stamps past +-2^62 ns (year 2116; a pcapng's offset can say so) subtract as floats here: no
     * difference of two kept stamps then overflows. */
    t->exact = !overflow && t->ns > -(1LL << 62) && t->ns < (1LL << 62);
    return 0;
}

/* (float, ns or None), or None: timedpath's Python side makes Stamps of them again. */
static PyObject *time_value(const Time *t) {
    if (!t->has) Py_RETURN_NONE;
    if (t->exact) return Py_BuildValue("(dL)", t->d, t->ns);
    return Py_BuildValue("(dO)", t->d, Py_None);
}

/* ---- tallies: (kind, key) -> a count or a sum, for every histogram of the report and the counts ---- */
typedef struct {
    uint64_t tag; /* (TALLY_* + 1) << 24 | its owner (slave << 8 | function, slave, poll order) */
    long long key;
    double value; /* counts too: exact up to 2^53 */
} Tally;

static size_t tally_hash(const void *key) {
    const Tally *t = key;
    return (size_t)mix(t->tag * 0x9E3779B97F4A7C15ULL ^ (uint64_t)t->key);
}

static const DenseKind TALLY_KIND = {sizeof(Tally), offsetof(Tally, value), 768, tally_hash};

/* A kind's histograms together hold at most `limit` entries (stats_store.MAX_TALLY; 0: no limit): past
 * it, every key of the kind is rounded down to a multiple of 2^shift, shift growing by one until they
 * fit (stats_store.Coarse, the Python stages' twin). The result depends on the values only, not on
 * their order: the smallest shift at which they all fit. */
typedef struct {
    Dense d; /* of Tally */
    size_t limit;
    int shift;
} Tallies;

static double *tally(Tallies *t, uint64_t tag, long long key) {
    Tally probe = {tag, key, 0.0}, *entry = dense_find(&t->d, &TALLY_KIND, &probe);
    if (entry == NULL) entry = dense_add(&t->d, &TALLY_KIND, &probe, t->limit); /* up to the limit + 1: it */
    return entry != NULL ? &entry->value : NULL; /* coarsens then, unless a shift of 62 does not fit */
}

/* One step coarser: every key rounded down to a multiple of 2^(shift + 1), equal keys merged (in place:
 * the k-th entry goes to the k-th position or before; fewer: no growth). */
static void tally_coarsen(Tallies *t) {
    size_t n = t->d.count;
    dense_clear(&t->d);
    t->shift++;
    long long mask = -(1LL << t->shift);
    for (size_t k = 0; k < n; k++) {
        Tally old = ((Tally *)t->d.items)[k];
        *tally(t, old.tag, old.key & mask) += old.value;
    }
}

/* t: the TALLIES tables, one a kind (the small ones stay in cache). */
static int tally_add(Tallies *t, int kind, long long owner, long long key, double amount) {
    Tallies *table = &t[kind];
    double *value = tally(table, (uint64_t)(kind + 1) << 24 | (uint32_t)owner, key & -(1LL << table->shift));
    if (value == NULL) return -1;
    *value += amount;
    while (table->limit && table->d.count > table->limit && table->shift < TALLY_MAX_SHIFT) tally_coarsen(table);
    return 0;
}

/* ---- bustiming.BusTiming -------------------------------------------------------------------------- */
typedef struct {
    double low, high;
} Quantile; /* bustiming.Quantiles: its buckets are tallies (and its count their sum: bustiming._quantiles) */

typedef struct {
    int active, slave;
    Time start, end;
    unsigned long long requests, first_frame, last_frame;
    long long offset;
    unsigned first_input, last_input; /* the files of its first and last request (input below) */
} Run;

#define GAP_BINS (sizeof gap_edges_ms / sizeof *gap_edges_ms + 1)

typedef struct {
    double char_time, t35, timeout;
    int timed;
    unsigned long long untimed;
    Time first;
    int has_last_end, has_answer_end;
    double last_end, busy, answer_end;
    Quantile gaps, turnaround, responses[256];
    unsigned long long histogram[GAP_BINS], below_t35, close[256];
    /* BusTiming.waits: per slave the longest wait after a request was sent (its response time less `sent`,
     * the seconds the last request took to send: an answer follows its request) */
    double waits[256], sent;
    unsigned long long same_stamp_overlaps; /* BusTiming.same_stamp_overlaps */
    Run runs[256];
    /* The file read, from 0 (bus_line's new inputs): several read as one bus number their frames each
     * from 1, so an outage names the files of its frames (BusTiming.new_input). */
    unsigned input;
    Run *outages; /* closed runs of two requests or more */
    size_t outage_count, outage_cap;
    Time first_seen, last_seen; /* StatsCollector.first_time, last_time */
    /* Time going backwards (BusTiming.backwards): items stamped before the item before them; the time of the
     * item before; where the items' stretch of forward time starts, its latest end so far, and the spans of
     * the stretches before it. */
    unsigned long long backwards;
    Time previous, stretch;
    double reach, spanned;
} Bus;

static void quantile_init(Quantile *q) {
    q->low = INFINITY;
    q->high = -INFINITY;
}

static void bus_init(Bus *b) {
    memset(b, 0, sizeof *b);
    quantile_init(&b->gaps);
    quantile_init(&b->turnaround);
    for (int k = 0; k < 256; k++) quantile_init(&b->responses[k]);
}

/* Quantiles.add: a RESOLUTION bucket (their sum the count), min, max. */
static int quantile_add(Tallies *t, Quantile *q, int kind, long long owner, double value) {
    if (tally_add(t, kind, owner, (long long)rint(value / RESOLUTION), 1.0) < 0) return -1;
    if (value < q->low) q->low = value;
    if (value > q->high) q->high = value;
    return 0;
}

/* Python's float // float (CPython's _float_div_mod). */
static double floor_div(double vx, double wx) {
    double mod = fmod(vx, wx), div = (vx - mod) / wx;
    if (mod && ((wx < 0) != (mod < 0))) div -= 1.0;
    if (!div) return copysign(0.0, vx / wx);
    double result = floor(div);
    return div - result > 0.5 ? result + 1.0 : result;
}

static int close_run(Bus *b, int slave) {
    Run *run = &b->runs[slave];
    run->active = 0;
    if (run->requests < 2) return 0;
    if (grow(&b->outages, &b->outage_cap, b->outage_count + 1, sizeof *b->outages, 16) < 0) return -1;
    b->outages[b->outage_count++] = *run;
    return 0;
}

enum { ITEM_NOISE = 0 }; /* else KIND_REQUEST, KIND_RESPONSE, KIND_EXCEPTION (_summary.c) */

/* StatsCollector.add's first and last times. */
static inline void stats_seen(Bus *b, const Time *t) {
    if (!t->has) return;
    if (!b->first_seen.has) b->first_seen = *t;
    b->last_seen = *t;
}

/* BusTiming.add, for one item: `sent`, the seconds from its first byte's time until its last byte was sent
 * (model.sent_in); `response`: its response time, NULL for none (a negative one never comes: BusTiming.add
 * and the engine's pairing leave it out); 0 or -1 (no memory). */
static int bus_add(Tallies *tallies, Bus *b, const Time *t, long long length, double sent, int kind, int slave,
                   int broadcast, int unanswered, int crc_ok, const double *response, unsigned long long number,
                   long long offset) {
    if (!t->has) {
        b->untimed++;
        return 0;
    }
    b->timed = 1;
    double duration = (double)length * b->char_time, end = t->d + sent;
    int same_stamp = b->previous.has && time_sub(t, &b->previous) == 0;
    if (!b->first.has) {
        b->first = b->stretch = *t;
        b->reach = end;
    } else if (time_sub(t, &b->previous) < 0) { /* time goes backwards: a new stretch */
        b->backwards++;
        b->spanned += b->reach - b->stretch.d;
        b->stretch = *t;
        b->reach = end;
        b->has_last_end = b->has_answer_end = 0; /* no gap, no turnaround to it */
    } else if (end > b->reach) {
        b->reach = end;
    }
    b->previous = *t;
    b->busy += duration;
    if (tally_add(tallies, TALLY_MINUTES, 0, (long long)floor_div(time_sub(t, &b->first), MINUTE), duration) < 0)
        return -1;
    if (b->has_last_end) {
        double gap = t->d - b->last_end;
        if (quantile_add(tallies, &b->gaps, TALLY_GAPS, 0, gap) < 0) return -1;
        if (gap < b->t35) b->below_t35++;
        if (same_stamp && rint(gap / RESOLUTION) < 0) b->same_stamp_overlaps++;
        size_t index = 0;
        while (index < GAP_BINS - 1 && gap * 1000 >= gap_edges_ms[index]) index++;
        b->histogram[index]++;
    }
    if (!b->has_last_end || end > b->last_end) b->last_end = end;
    b->has_last_end = 1;
    if (kind == ITEM_NOISE) return 0;
    if (kind == KIND_REQUEST) {
        b->sent = sent;
        if (b->has_answer_end && quantile_add(tallies, &b->turnaround, TALLY_TURNAROUND, 0, t->d - b->answer_end) < 0)
            return -1;
        b->has_answer_end = 0;
        if (broadcast) return 0;
        Run *run = &b->runs[slave];
        if (unanswered) {
            if (!run->active) {
                *run = (Run){1, slave, *t, *t, 1, number, number, offset, b->input, b->input};
            } else {
                run->end = *t;
                run->requests++;
                run->last_frame = number;
                run->last_input = b->input;
            }
        } else if (run->active && close_run(b, slave) < 0) {
            return -1;
        }
        return 0;
    }
    b->has_answer_end = 1;
    b->answer_end = end;
    if (response != NULL && crc_ok) {
        int first = b->responses[slave].low > b->responses[slave].high; /* (no response time yet) */
        if (quantile_add(tallies, &b->responses[slave], TALLY_RESPONSES, slave, *response) < 0) return -1;
        double wait = *response - b->sent; /* (as pairing.py _late subtracts) */
        if (first || wait > b->waits[slave]) b->waits[slave] = wait;
        if (wait > CLOSE_MARGIN * b->timeout) b->close[slave]++;
    }
    return 0;
}
