/* The compiled summary path of vw3-decode: raw Modbus RTU bytes in, summary lines out.
 *
 * It does, for the transactions of every public function code the protocol table marks compiled
 * (protocol/table.py, through _tables.h: requests, their normal responses, unanswered requests and
 * exceptions), exactly what the Python stages do: the framer's fast path (framing/rtu.py, _run),
 * pairing, the decoder's spec checks, the annotator's naming (PLC-style addresses included) and
 * parameter tracking, and the summary line (render/summary.py); FC8's texts too (the spec's
 * sub-function names, from _tables.h). For FC17, FC20, FC21 and FC43 (table.Compiled.texts), and for
 * exceptions, it frames and pairs, and the texts come from the Python stages by the frames' bytes. What
 * it hands back, before touching any state, at the start of the transaction, and why:
 *   - noise, a damaged frame, a frame followed by a 00 byte, a length only a CRC scan finds (FC43
 *     other than 14): the framer's careful path decides those (inside a noise run it has open, the
 *     engine frames the noise for it: _noise.h). FC8's Return Query Data, whose echo
 *     has no length either, is found here by the framer's own scan (scan_length: the shortest CRC
 *     match an intact frame follows, checked with the framer's rules for every code it knows);
 *   - user-defined and vendor codes (SEL-749M 60h...): no layout, nothing to show but bytes;
 *   - a reserved address (248..255): the decoder's warning; glitch bytes between frames (a real
 *     line's turn-around): noise, the careful path's, which weighs the evidence around them;
 *   - an exception to FC17, FC20, FC21 or FC43;
 *   - broadcasts, answers nobody asked for, mismatched answers: pairing's findings are notes;
 *   - anything that carries a warning or a note: spec limits, byte counts, coil values other than
 *     ON/OFF, FC5/FC6 answers that do not echo their request, FC8 sub-functions the spec does not
 *     define or the device explains, odd FC8 data, requests beyond the device's limits or not
 *     supported by it, 16#8000 in a multi-word read, a parameter readable again, a bits_depend switch;
 *   - exception 2 to an FC3/FC4 read on a device that protects parameters (ATV71, p.38): the
 *     annotator then forgets the values of every parameter read, a change of state;
 *   - a slave whose annotator the engine knows nothing of, or whose PLC-style base is odd.
 * The Python stages then take that part of the stream, and give it back at their next idle point
 * (dissector/accel/fastsummary.py). tests/differential/test_fastsummary.py holds the output of both
 * paths equal; bench/fastsummary_fuzz.py runs the same comparison for as long as asked.
 *
 * Device knowledge stays in Python: register texts come from a callback (the annotator and the
 * summary renderer themselves), cached here by (slave, function, address, value); the texts of a
 * transaction it does not write itself (an exception, with the device's explanation) come from
 * another, cached there by request and answer.
 *
 * One file on purpose: a single translation unit lets the compiler inline the per-byte helpers
 * (CRC, words, output) into the transaction loop without link-time optimisation.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* Every rule per function code, and the constants shared with the Python stages, are generated from
 * the protocol table and its rule tables (python3 -m dissector.codegen; codegen/c.py, c_rules.py): no
 * function code is named below, the checks and lines interpret `rules`, `request_lift`, `response_lift`
 * and the length rules. */
#include "_tables.h"

#define PIECES (1 << 16) /* register texts cached at most */

enum { FRAME_OK = 0, FRAME_NEED = -1, FRAME_HANDOVER = -2 };

static uint16_t crc16(const uint8_t *p, Py_ssize_t n) {
    uint16_t crc = 0xFFFF;
    while (n--) crc = (uint16_t)((crc >> 8) ^ crc_table[(crc ^ *p++) & 0xFF]);
    return crc;
}

static inline unsigned word(const uint8_t *p) { return (unsigned)p[0] << 8 | p[1]; }
static unsigned field(const uint8_t *f, int at, int width) { return width == 2 ? word(f + at) : f[at]; }

/* ---- growing arrays: the output, the memory log, dense tables, outages, --report's columns -------- */
/* The array whose address is at `array` (a T **, any T; *cap items of `size` bytes) reallocated to `to`
 * items: 0, or -1 with MemoryError set and the array unchanged. */
static int resize(void *array, size_t *cap, size_t to, size_t size) {
    void *items;
    memcpy(&items, array, sizeof items);
    if ((items = PyMem_Realloc(items, to * size)) == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    memcpy(array, &items, sizeof items);
    *cap = to;
    return 0;
}

/* The same array made to hold `need` items, its room doubled from `first` as needed. */
static inline int grow(void *array, size_t *cap, size_t need, size_t size, size_t first) {
    if (need <= *cap) return 0;
    size_t to = *cap ? *cap : first;
    while (to < need) to *= 2;
    return resize(array, cap, to, size);
}

/* ---- dense tables: items in the order first made, in an array grown by half at a time, found through
 * an index of `size` slots (a power of two, at most 3/4 used): 1 + an item's position, 0: empty. An
 * item's key is its first `key` bytes (no padding in them). Open addressing of the items themselves took
 * twice their room: 65,536 tallies of 24 bytes took 131,072 slots, 3 MB a kind. ------------------- */
typedef struct {
    size_t item, key, first;         /* the bytes of an item and of its key; the first allocation: 3 << k */
    size_t (*hash)(const void *key); /* of a key, or of an item (its key comes first) */
} DenseKind;

typedef struct {
    char *items;
    uint32_t *index;
    size_t size, count, cap, hole; /* hole: the empty slot where the last dense_find stopped */
} Dense;

/* The item of `key`, or NULL (d->hole: where it goes). */
static inline void *dense_find(Dense *d, const DenseKind *kind, const void *key) {
    if (!d->size) return NULL;
    size_t slot = kind->hash(key) & (d->size - 1);
    for (uint32_t at; (at = d->index[slot]) != 0; slot = (slot + 1) & (d->size - 1))
        if (memcmp(d->items + (at - 1) * kind->item, key, kind->key) == 0) return d->items + (at - 1) * kind->item;
    d->hole = slot;
    return NULL;
}

/* A new item of `key` after dense_find missed it: zeroed, its key copied; NULL with an exception set (no
 * memory). The array grows up to most + 1 items at first (0: no bound; more when the owner lets it). */
static void *dense_add(Dense *d, const DenseKind *kind, const void *key, size_t most) {
    if (d->count == d->cap) {
        size_t cap = d->cap ? d->cap + d->cap / 2 : kind->first;
        cap = most && d->cap <= most && cap > most + 1 ? most + 1 : cap;
        if (resize(&d->items, &d->cap, cap, kind->item) < 0) return NULL;
    }
    if (4 * (d->count + 1) > 3 * d->size) {
        size_t size = d->size ? 2 * d->size : kind->first / 3 * 4;
        uint32_t *index = PyMem_Calloc(size, sizeof *index);
        if (index == NULL) return PyErr_NoMemory();
        PyMem_Free(d->index);
        d->index = index, d->size = size;
        for (size_t k = 0, slot; k < d->count; index[slot] = (uint32_t)++k)
            for (slot = kind->hash(d->items + k * kind->item) & (size - 1); index[slot]; slot = (slot + 1) & (size - 1)) {}
        (void)dense_find(d, kind, key);
    }
    char *item = d->items + d->count * kind->item;
    memset(item, 0, kind->item);
    memcpy(item, key, kind->key);
    d->index[d->hole] = (uint32_t)++d->count;
    return item;
}

/* Every item gone, the room kept. */
static void dense_clear(Dense *d) {
    d->count = 0;
    if (d->index != NULL) memset(d->index, 0, d->size * sizeof *d->index);
}

static void dense_free(Dense *d) {
    PyMem_Free(d->items);
    PyMem_Free(d->index);
}

static uint64_t mix(uint64_t key) { /* splitmix64's finaliser: keys differ in a few low bits */
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebULL;
    return key ^ (key >> 31);
}

static size_t key_hash(const void *key) { return (size_t)mix(*(const uint64_t *)key); } /* (a 64-bit key) */

/* ---- Python objects made in C: dict[key] = value and list.append(item) of new references, which they release
 * (NULL: the error of making one, already set): 0, or -1 with an exception set. ---------------------------- */
static int dict_put(PyObject *dict, PyObject *key, PyObject *value) {
    int status = key != NULL && value != NULL ? PyDict_SetItem(dict, key, value) : -1;
    Py_XDECREF(key);
    Py_XDECREF(value);
    return status;
}

/* The references at these places released, the places emptied (the types' clean-up). */
#define CLEAR_ALL(...) clear_all((PyObject **[]){__VA_ARGS__}, sizeof (PyObject **[]){__VA_ARGS__} / sizeof(PyObject **))
static void clear_all(PyObject **const *held, size_t n) {
    for (size_t k = 0; k < n; k++) Py_CLEAR(*held[k]);
}

/* A getter of the object at offset `closure` in its owner (Engine.stats and judge, Stats.report); NULL: None. */
static PyObject *object_get(PyObject *owner, void *closure) {
    PyObject *value = *(PyObject **)((char *)owner + (size_t)closure);
    return Py_NewRef(value != NULL ? value : Py_None);
}

/* An exception of `type` set: -1 (PyErr_Format's NULL, for the functions that answer an int). */
static int fail(PyObject *type, const char *text) {
    PyErr_SetString(type, text);
    return -1;
}

static int list_put(PyObject *list, PyObject *item) {
    int status = item != NULL ? PyList_Append(list, item) : -1;
    Py_XDECREF(item);
    return status;
}

/* ---- output buffer ---------------------------------------------------------------------------- */
/* Lines being written. After a failed allocation, `failed` is set with MemoryError raised; writers
 * check it once per line. */
typedef struct { char *data; size_t len, cap; int failed; } Out;

static int out_reserve(Out *o, size_t more) {
    if (o->failed) return -1;
    if (grow(&o->data, &o->cap, o->len + more, 1, 1 << 16) == 0) return 0;
    o->failed = 1;
    return -1;
}

static void out_put(Out *o, const char *s, size_t n) {
    if (out_reserve(o, n) < 0) return;
    memcpy(o->data + o->len, s, n);
    o->len += n;
}

static void out_cstr(Out *o, const char *s) { out_put(o, s, strlen(s)); }

/* v in base 10 or 16 (upper case), right-aligned in `width` characters with `pad`: Python's
 * f"{v:{width}}" and f"{v:0{width}X}". */
static inline void out_number(Out *o, unsigned long long v, unsigned radix, int width, char pad) {
    char digits[24];
    int n = 0;
    do { digits[n++] = "0123456789ABCDEF"[v % radix]; v /= radix; } while (v);
    if (out_reserve(o, (size_t)(n > width ? n : width)) < 0) return;
    for (int fill = width - n; fill > 0; fill--) o->data[o->len++] = pad;
    while (n) o->data[o->len++] = digits[--n];
}

static inline void out_uint(Out *o, unsigned long long v, int width) { out_number(o, v, 10, width, ' '); }

/* describe.py's tail of `count` items past the first `shown`: `… (+n)`, `… (+n bytes)` (`lead` before it, `end`
 * ")" or " bytes)"); none when they were all shown. */
static inline void out_more(Out *o, unsigned long long count, unsigned long long shown, const char *lead, const char *end) {
    if (count <= shown) return;
    out_cstr(o, lead);
    out_cstr(o, "\xe2\x80\xa6 (+");
    out_uint(o, count - shown, 0);
    out_cstr(o, end);
}

static int out_str(Out *o, PyObject *text) {
    Py_ssize_t n;
    const char *s = PyUnicode_AsUTF8AndSize(text, &n);
    if (s == NULL) return -1;
    out_put(o, s, (size_t)n);
    return o->failed ? -1 : 0;
}

/* naming.plc_label: five digits at least, zero-padded (coil references: 00001), one more past the top
 * of the base's range (40001 + address up to 49999, then 410000); base < 0: the address itself. */
static inline void out_label(Out *o, long long base, unsigned address) {
    if (base < 0) {
        out_uint(o, address, 0);
        return;
    }
    int digits = 5; /* the base's digits, five at least; power: 10 ** (digits - 1) */
    long long power = 10000;
    while (power * 10 <= base) {
        power *= 10;
        digits++;
    }
    long long number = base + address;
    if (number > (base / power + 1) * power - 1) {
        number = base * 10 - 9 + address;
        digits++;
    }
    out_number(o, (unsigned long long)number, 10, digits, '0');
}

/* ---- per-slave knowledge, from the Python callback slave_info(slave) -------------------------- */
#include "_timeline.h" /* the chunks of a timed source (pcap records) */
#include "_records.h"  /* pcap records read in bulk */

typedef struct {
    int loaded;
    int usable;               /* 0: every transaction of this slave goes to Python */
    PyObject *info;           /* the SlaveFacts' items as a tuple, which keeps the objects below alive */
    PyObject *name[HANDLED];  /* function names as shown */
    int check[HANDLED];       /* -1: hand over; 0: no device limit; 1, 2: limits below */
    long limit[HANDLED][2];
    PyObject *depend;         /* dict address -> (on, frozenset plain_when) */
    /* Address sets as bitmaps (one bit per address): tested for every register, at C speed. */
    uint8_t *mapped;          /* addresses the annotator names */
    uint8_t *dependent;       /* addresses with a bits_depend rule */
    uint8_t *sources;         /* the addresses those rules depend on */
    uint8_t *pending;         /* addresses whose newest memory entry is in the engine's log */
    uint8_t *explained;       /* FC8 sub-functions the device explains or lacks (a note, a warning: Python's) */
    uint8_t *read_only;       /* read-only parameters: a write of one is warned (access.check_writes) */
    long long base[HANDLED];  /* PLC-style display: 40001 + address (naming.plc_label); -1: none */
    unsigned long depend_run; /* the run() the answer below was found in */
    unsigned depend_address;
    int depend_plain;
    PyObject *seen;           /* the annotator's dict, or NULL when it tracks nothing */
    long protected_value;     /* -1: none */
    PyObject *namer;          /* (address, value) -> (text, code) with this slave's device, for --stats */
} Slave;

/* One entry of the annotator's parameter memory, kept here until the end of run(): a polled register
 * is written once per run into the dict instead of once per read. */
typedef struct {
    unsigned long long number;
    uint16_t address, value;
    uint8_t slave, written;
} Remembered;

typedef struct {
    uint64_t key;
    PyObject *text;   /* owned */
    const char *utf8; /* text's own UTF-8 form */
    Py_ssize_t length;
    int named;
} PieceSlot;

/* What the framer weighs besides the bytes (framing/rtu.py RtuFramer, rules.Awaiting): the answer awaited, the
 * line's habit, and where records end: the engine's chunks (tl, while run_timed() runs), or noise_span's lists. */
typedef struct {
    const uint8_t *b;                  /* the bytes: run()'s buffer, or the framer's (noise_span) */
    Py_ssize_t size;
    int expect_slave, expect_function; /* the answer awaited, -1: none */
    const uint8_t *echo;               /* what it must repeat of its request (_echo; the engine's: nothing) */
    Py_ssize_t echo_length;
    char glitchy;                      /* StreamFramer.glitchy: the line leaves 00 glitches (set at each hand-back) */
    Timeline *tl;                      /* the engine's: record ends where tl->active; NULL: the lists below */
    const Py_ssize_t *ends, *starts;   /* noise_span's record ends (_boundaries) and starts (_record_starts), */
    Py_ssize_t end_count, start_count; /* ascending, as buffer indexes */
    signed char *ends_record;          /* by record end: ends_record's answer, -1 not asked yet (the framer's
                                        * _ends_memo: the buffer and the state stay in one noise_span call) */
} Line;

typedef struct {
    PyObject_HEAD
    unsigned long long count;
    Line line; /* the framer's state (its bytes: run()'s buffer) */
    PyObject *slave_info;
    PyObject *piece;
    PyObject *texts;     /* texts(slave, request, answer or None) -> Texts or None (hand over) */
    Dense pieces;        /* of PieceSlot: (slave, function, address, value) -> the register's text */
    unsigned long run_number; /* bits_depend answers are kept for one run() (see register_is_plain) */
    PyObject *read_word, *written_word;
    Slave slaves[256];
    Out out;
    Remembered *log;
    size_t log_len, log_cap;
    int running; /* inside run(): callbacks must not re-enter */
    PyObject *stats; /* a Stats (_stats.h) counting what is shown here, or NULL: summary only */
    Timeline tl;     /* run_timed(): the chunks and times of the stream (_timeline.h) */
    PyObject *judge;       /* profile auto's first pass (_judge.h): its bitmap (bytes), or NULL */
    char frames;           /* with judge: each transaction passed is written out as a record (_judge.h) */
} Engine;

#define BITMAP_BYTES (65536 / 8)
#define SLAVE_BITMAPS(s) \
    {&(s)->mapped, &(s)->dependent, &(s)->sources, &(s)->pending, &(s)->explained, &(s)->read_only}
#define SLAVE_SETS 6
static const uint8_t no_addresses[BITMAP_BYTES]; /* an empty set's bitmap, shared (only pending is written) */

static void slave_clear(Slave *s) {
    Py_CLEAR(s->info);
    uint8_t **bitmaps[SLAVE_SETS] = SLAVE_BITMAPS(s);
    for (int k = 0; k < SLAVE_SETS; k++) {
        if (*bitmaps[k] != no_addresses) PyMem_Free(*bitmaps[k]);
        *bitmaps[k] = NULL;
    }
    s->depend_run = 0;
    s->loaded = 0;
}

static inline int bit(const uint8_t *bitmap, unsigned address) {
    return bitmap[address >> 3] >> (address & 7) & 1;
}

/* Set the bits of the integer addresses an iterable (set, dict) holds; others cannot be sent. */
static int fill_bitmap(uint8_t *bitmap, PyObject *addresses) {
    PyObject *iterator = PyObject_GetIter(addresses);
    if (iterator == NULL) return -1;
    PyObject *item;
    while ((item = PyIter_Next(iterator)) != NULL) {
        long address = PyLong_AsLong(item);
        Py_DECREF(item);
        if (address == -1 && PyErr_Occurred()) break;
        if (address >= 0 && address < 65536) bitmap[address >> 3] |= (uint8_t)(1 << (address & 7));
    }
    Py_DECREF(iterator);
    return PyErr_Occurred() ? -1 : 0;
}

static int bad_info(const char *what) {
    PyErr_Format(PyExc_TypeError, "slave_info: %s", what);
    return -1;
}

/* The attributes `names` of a callback's answer (`what`: which, for the error) as a tuple in that order:
 * a fastsummary.SlaveFacts (fact_names, _tables.h; the slave keeps the tuple, its items are borrowed
 * while it lives) or Texts (text_names, read for every transaction whose texts are Python's). `keys`: the
 * names as interned str, made on first use (a str from a C string at every read cost more than the read). */
static PyObject *read_fields(PyObject *object, const char *const *names, PyObject **keys, int count, const char *what) {
    PyObject *tuple = PyTuple_New(count);
    if (tuple == NULL) return NULL;
    for (int k = 0; k < count; k++) {
        if (keys[k] == NULL && (keys[k] = PyUnicode_InternFromString(names[k])) == NULL) {
            Py_DECREF(tuple);
            return NULL;
        }
        PyObject *value = PyObject_GetAttr(object, keys[k]);
        if (value == NULL) {
            if (PyErr_ExceptionMatches(PyExc_AttributeError)) {
                PyErr_Clear();
                PyErr_Format(PyExc_TypeError, "%s: no %s", what, names[k]);
            }
            Py_DECREF(tuple);
            return NULL;
        }
        PyTuple_SET_ITEM(tuple, k, value);
    }
    return tuple;
}

/* A dict's entry for the k-th handled function code (borrowed), NULL: none or an error. */
static PyObject *code_entry(PyObject *dict, int k) {
    PyObject *code = PyLong_FromLong(handled_codes[k]);
    PyObject *entry = code ? PyDict_GetItemWithError(dict, code) : NULL;
    Py_XDECREF(code);
    return entry;
}

static int fill_slave(Slave *s, PyObject *info) {
    PyObject *facts[FACTS];
    for (int k = 0; k < FACTS; k++) facts[k] = PyTuple_GET_ITEM(info, k);
    s->usable = PyObject_IsTrue(facts[FACT_USABLE]);
    if (s->usable <= 0) return s->usable;
    PyObject *functions = facts[FACT_FUNCTIONS];
    PyObject *seen = facts[FACT_SEEN];
    PyObject *bases = facts[FACT_BASES];
    if (!PyDict_Check(functions) || !PyAnySet_Check(facts[FACT_MAPPED]) || !PyDict_Check(facts[FACT_DEPEND]) ||
        !PyAnySet_Check(facts[FACT_SOURCES]) || !PyAnySet_Check(facts[FACT_DIAGNOSTICS]) ||
        !PyAnySet_Check(facts[FACT_READ_ONLY]) ||
        (seen != Py_None && !PyDict_Check(seen)) ||
        (bases != Py_None && !PyDict_Check(bases)))
        return bad_info("facts of the wrong type");
    for (int k = 0; k < HANDLED; k++) { /* its entries in functions and bases (None: protocol addresses) */
        PyObject *entry = code_entry(functions, k);
        PyObject *base = bases == Py_None || entry == NULL ? Py_None : code_entry(bases, k);
        if (entry == NULL || base == NULL || !PyTuple_Check(entry) || PyTuple_GET_SIZE(entry) != 2 ||
            !PyUnicode_Check(PyTuple_GET_ITEM(entry, 0))) {
            if (!PyErr_Occurred()) bad_info(base == NULL ? "no PLC base for a function" : "bad function entry");
            return -1;
        }
        s->name[k] = PyTuple_GET_ITEM(entry, 0);
        PyObject *check = PyTuple_GET_ITEM(entry, 1);
        Py_ssize_t n = check == Py_None ? -1 : PyTuple_Size(check); /* None: every request to the annotator */
        s->check[k] = n > 2 ? -1 : (int)n;
        for (Py_ssize_t j = 0; j < n && j < 2; j++) s->limit[k][j] = PyLong_AsLong(PyTuple_GET_ITEM(check, j));
        s->base[k] = base == Py_None ? -1 : PyLong_AsLongLong(base);
        if (PyErr_Occurred()) return -1;
        if (base != Py_None && (s->base[k] < 1 || s->base[k] > 999999999))
            s->usable = 0; /* odd labels: leave them to Python */
    }
    s->depend = facts[FACT_DEPEND];
    /* (a generic profile's slaves kept 4 x 8 KB of zeros each: 247 of them 8 MB; issue 28) */
    PyObject *sets[SLAVE_SETS] = {facts[FACT_MAPPED], s->depend, facts[FACT_SOURCES], NULL,
                                  facts[FACT_DIAGNOSTICS], facts[FACT_READ_ONLY]};
    uint8_t **bitmaps[SLAVE_SETS] = SLAVE_BITMAPS(s);
    for (int k = 0; k < SLAVE_SETS; k++) {
        Py_ssize_t n = sets[k] != NULL ? PyObject_Size(sets[k]) : seen != Py_None; /* (pending: track()'s) */
        *bitmaps[k] = n == 0 ? (uint8_t *)no_addresses : n > 0 ? PyMem_Calloc(1, BITMAP_BYTES) : NULL;
        if (*bitmaps[k] == NULL) return n < 0 ? -1 : (PyErr_NoMemory(), -1);
        if (n > 0 && sets[k] != NULL && fill_bitmap(*bitmaps[k], sets[k]) < 0) return -1;
    }
    s->seen = seen == Py_None ? NULL : seen;
    s->namer = facts[FACT_NAMER];
    s->protected_value = PyLong_AsLong(facts[FACT_PROTECTED]);
    if (PyErr_Occurred()) return -1;
    return 0;
}

static __attribute__((noinline)) int load_slave(Engine *e, int address) { /* (off the path of every transaction) */
    Slave *s = &e->slaves[address];
    PyObject *answer = PyObject_CallFunction(e->slave_info, "i", address);
    if (answer == NULL) return -1;
    static PyObject *keys[FACTS];
    PyObject *info = read_fields(answer, fact_names, keys, FACTS, "slave_info (a fastsummary.SlaveFacts)");
    Py_DECREF(answer);
    if (info == NULL) return -1;
    slave_clear(s); /* the callback may have loaded it already */
    s->info = info;
    if (fill_slave(s, info) < 0) {
        slave_clear(s);
        return -1;
    }
    s->loaded = 1;
    return 0;
}

/* ---- framing: framing/rtu.py's fast path, for the codes handled here -------------------------- */
typedef struct {
    Py_ssize_t at, length;
    int kind, slave, function;
    int timed;           /* run_timed(): the frame's chunk has a time, ns */
    long long ns;
    long long before;    /* run_timed() with befores: the time of the packet before its first (_timeline.h) */
    long long decided;   /* run_timed(): the Python framer's buffer end when it takes this frame */
    /* model.Tail: the time of the chunk holding its last byte and the bytes from that chunk's start to the
     * frame's end (ns and length where that chunk is its first and starts at it, or there are no times) */
    long long tail_ns;
    Py_ssize_t tail_chars;
} FrameRef;

/* model.sent_in: seconds from the frame's first byte's time until its last byte was sent (its length at the
 * line's speed, or later where its last byte's chunk says so). */
static inline double frame_sent(const FrameRef *f, double char_time) {
    double sent = (double)f->length * char_time, last = stamp_seconds(f->tail_ns, f->ns) + (double)f->tail_chars * char_time;
    return last > sent ? last : sent;
}

/* The frame of `length` bytes at i ends in the CRC of the bytes before it. */
static inline int crc_ok(const uint8_t *b, Py_ssize_t i, Py_ssize_t length) {
    Py_ssize_t stop = i + length - 2;
    return crc16(b + i, length - 2) == (uint16_t)(b[stop] | b[stop + 1] << 8);
}

/* A length rule's answer as framing/rules.py gives it: a length (0: the layout cannot apply), more
 * bytes needed, or a CRC scan from a minimum length (its Scan; `declared`: the length its own fields
 * declare, Scan.declared, -1 where they run past the bytes there, 0 none). */
enum { LENGTH_OK, LENGTH_NEED, LENGTH_SCAN };
typedef struct { int what; Py_ssize_t value, declared; } Length;

static Length rule_length(const LengthRule *rule, const uint8_t *b, Py_ssize_t i, Py_ssize_t n) {
    const Length need = {LENGTH_NEED, 0};
    if (rule->fixed) return (Length){LENGTH_OK, rule->fixed};
    if (rule->special == RULE_SCAN) return (Length){LENGTH_SCAN, rule->extra};
    if (i + rule->position + rule->width - 1 >= n) return need;
    Py_ssize_t value = field(b + i, rule->position, rule->width);
    switch (rule->special) {
    case RULE_SELECT:
        return rule_length(&selected_rule[value == rule->value ? rule->chosen : rule->otherwise], b, i, n);
    case RULE_BY_QUANTITY: { /* a request's length by its quantity where it differs from its byte count's */
        if (i + rule->count_at >= n) return need;
        Py_ssize_t length = rule->extra + (rule->unit ? value * rule->unit : (value + 7) / 8);
        return (Length){LENGTH_OK, length == rule->count_extra + b[i + rule->count_at] ? 0 : length};
    }
    case RULE_MEI_OBJECTS: { /* `value` objects from `extra`: an id, a length byte, that many bytes each */
        /* Where the walk does not end in a valid CRC (past the bytes there or an RTU frame, or its CRC
         * fails): a CRC scan from the list's start (rules.py _mei_objects), the careful path's. */
        Length fallback = {LENGTH_SCAN, rule->extra + 2, -1};
        Py_ssize_t stop = rule->extra;
        for (Py_ssize_t k = value; k > 0; k--) {
            if (i + stop + 1 >= n) return fallback;
            stop += 2 + b[i + stop + 1];
            if (stop > MAX_ADU) return (Length){LENGTH_SCAN, rule->extra + 2, 0};
        }
        fallback.declared = stop + 2;
        return i + stop + 2 <= n && crc_ok(b, i, stop + 2) ? (Length){LENGTH_OK, stop + 2, 0} : fallback;
    }
    default: /* counted */
        return (Length){LENGTH_OK, rule->extra + value};
    }
}

/* A CRC scan of the frame at i over the lengths minimum..maximum (crc.crc_lengths): crc_next gives, in
 * order, each length at which the bytes end in the CRC of the bytes before them, then 0; one CRC pass. */
typedef struct { const uint8_t *frame; Py_ssize_t length, maximum; uint16_t crc; } CrcScan;

static CrcScan crc_scan(const uint8_t *b, Py_ssize_t i, Py_ssize_t minimum, Py_ssize_t maximum) {
    if (minimum < 2) minimum = 2;
    return (CrcScan){b + i, minimum, maximum, minimum <= maximum ? crc16(b + i, minimum - 2) : 0};
}

static Py_ssize_t crc_next(CrcScan *scan) {
    for (; scan->length <= scan->maximum; scan->length++) {
        const uint8_t *stop = scan->frame + scan->length - 2;
        uint16_t crc = scan->crc;
        scan->crc = (uint16_t)((crc >> 8) ^ crc_table[(crc ^ stop[0]) & 0xFF]);
        if (crc == (uint16_t)(stop[0] | stop[1] << 8)) return scan->length++;
    }
    return 0;
}

/* RtuFramer._match's interpretations of a code, in its order (an exception's; else the awaited answer's first when
 * `expected`, the other, the request by its quantity where that differs): how many, in rules[]; 0: unknown. */
static int layouts(int function, int expected, const LengthRule *rules[3]) {
    int k = known_slot[function & 0x7F];
    if (k < 0) return 0;
    rules[0] = function & 0x80 ? &exception_rule : &known_rule[k][expected];
    rules[1] = &known_rule[k][!expected];
    rules[2] = &known_rule[k][LAYOUT_BY_QUANTITY];
    return function & 0x80 ? 1 : rules[2]->special ? 3 : 2;
}

/* A length rule at i with the bytes up to n, as the framer weighs one interpretation (RtuFramer
 * _valid_frame_at, _match): 1 it checks out, 0 it does not apply or fails its CRC, 2 it waits for more
 * bytes, -1 a CRC scan from *length bytes (*length: its length, -1 the bytes that give it). */
static int rule_check(const LengthRule *rule, const uint8_t *b, Py_ssize_t i, Py_ssize_t n, Py_ssize_t *length) {
    Length found = rule_length(rule, b, i, n);
    *length = found.what == LENGTH_NEED ? -1 : found.value;
    if (found.what != LENGTH_OK) return found.what == LENGTH_SCAN ? -1 : 2;
    if (*length < MIN_ADU || *length > MAX_COUNTED) return 0;
    return i + *length > n ? 2 : crc_ok(b, i, *length);
}

/* The first index of the sorted `at` (count) not below j. */
static Py_ssize_t lower_index(const Py_ssize_t *at, Py_ssize_t count, Py_ssize_t j) {
    Py_ssize_t low = 0, high = count;
    while (low < high) {
        Py_ssize_t middle = (low + high) / 2;
        if (at[middle] < j) low = middle + 1;
        else high = middle;
    }
    return low;
}

/* StreamFramer._boundary_at: a record ends, or a silence begins, at j. */
static inline int line_bound(const Line *L, Py_ssize_t j) {
    if (L->tl != NULL) return L->tl->active && boundary_at(L->tl, L->tl->base + j);
    Py_ssize_t k = lower_index(L->ends, L->end_count, j);
    return k < L->end_count && L->ends[k] == j;
}

/* Offsets.first_after: the first record end o with low < o <= high, or -1. */
static Py_ssize_t line_end_after(const Line *L, Py_ssize_t low, Py_ssize_t high) {
    Timeline *t = L->tl;
    if (t == NULL) {
        Py_ssize_t k = lower_index(L->ends, L->end_count, low + 1);
        return k < L->end_count && L->ends[k] <= high ? L->ends[k] : -1;
    }
    for (Py_ssize_t k = t->active ? chunk_of(t, t->base + low) : t->count; k < t->count; k++) {
        Py_ssize_t at = (Py_ssize_t)(chunk_end(t, k) - t->base);
        if (at > high) break;
        if (boundary_at(t, t->base + at)) return at;
    }
    return -1;
}

/* rules.Awaiting._awaited: the answer awaited starts at i (its echo compared as far as the bytes go). */
static int awaited(const Line *L, Py_ssize_t i) {
    int function = L->b[i + 1];
    if (L->b[i] != L->expect_slave || (function & 0x7F) != L->expect_function) return 0;
    if (!L->echo_length || function & 0x80) return 1;
    Py_ssize_t got = L->size - (i + 2);
    got = got < 0 ? 0 : got < L->echo_length ? got : L->echo_length;
    return memcmp(L->b + i + 2, L->echo, (size_t)got) == 0;
}

/* RecordEnds._ends_record: a layout at j checks out and ends at a record's end (a scanned one: the first after j). */
static int ends_record(const Line *L, Py_ssize_t j, Py_ssize_t n) {
    const LengthRule *rules[3];
    int count = layouts(L->b[j + 1], awaited(L, j), rules);
    for (int r = 0; r < count; r++) {
        Length found = rule_length(rules[r], L->b, j, n);
        Py_ssize_t length = found.what == LENGTH_NEED ? -1 : found.value, longest = MAX_COUNTED;
        if (found.what == LENGTH_SCAN) {
            Py_ssize_t end = line_end_after(L, j, n);
            length = end >= 0 && end - j >= found.value ? end - j : 0;
            longest = MAX_ADU;
        }
        if (length >= MIN_ADU && length <= longest && j + length <= n && line_bound(L, j + length) &&
            crc_ok(L->b, j, length))
            return 1;
    }
    return 0;
}

/* RecordEnds._framed_reach: where a CRC scan from i stops, the first record end after i that is a frame of its
 * own (within MAX_ADU), else n (n too without record ends: an untimed stream). */
static Py_ssize_t framed_reach(const Line *L, Py_ssize_t i, Py_ssize_t n) {
    Py_ssize_t high = n - MIN_ADU + 1 < i + MAX_ADU ? n - MIN_ADU + 1 : i + MAX_ADU;
    if (L->tl == NULL) { /* noise_span's record ends, each weighed once (the framer's _ends_memo) */
        for (Py_ssize_t k = lower_index(L->ends, L->end_count, i + 1); k < L->end_count && L->ends[k] < high; k++) {
            if (L->ends_record[k] < 0) L->ends_record[k] = (signed char)ends_record(L, L->ends[k], n);
            if (L->ends_record[k]) return L->ends[k];
        }
        return n;
    }
    for (Py_ssize_t at = i; (at = line_end_after(L, at, n)) > 0 && at < high;)
        if (ends_record(L, at, n)) return at;
    return n;
}

/* RecordEnds._crosses_framed_record: a reading at i of `length` bytes (-1: more than there are) would swallow a
 * record that is a frame of its own, the first one after i (framed_reach) starting inside it: it is none. */
static int crosses_framed_record(const Line *L, Py_ssize_t i, Py_ssize_t length, Py_ssize_t n) {
    Py_ssize_t reach = framed_reach(L, i, n);
    return reach < n && reach < (length < 0 ? n : i + length);
}

/* RtuFramer._valid_frame_at with the bytes up to n: 1 an intact frame starts at j, 0 none, -1 more bytes needed
 * to know (`final`: none will come); `scan` 0: layouts without a length rule not tried. The interpretations are
 * the framer's, in its order for the answer awaited (any address: 248..255 are framed too, reserved). */
static int valid_frame_at(const Line *L, Py_ssize_t j, Py_ssize_t n, int final, int scan) {
    if (n - j < MIN_ADU) return final ? j == n : -1;
    const LengthRule *rules[3];
    int count = layouts(L->b[j + 1], awaited(L, j), rules);
    int undecided = 0; /* a CRC scan found nothing yet, but a longer frame may still arrive */
    for (int r = 0; r < count; r++) {
        Length found = rule_length(rules[r], L->b, j, n);
        if (found.what == LENGTH_SCAN) {
            if (!scan) continue;
            Py_ssize_t reach = framed_reach(L, j, n); /* (not across a record that is a frame: _shortest_crc) */
            CrcScan crcs = crc_scan(L->b, j, found.value, reach - j < MAX_ADU ? reach - j : MAX_ADU);
            if (crc_next(&crcs)) return 1;
            undecided = undecided || (!final && reach == n && n - j < MAX_ADU);
            continue;
        }
        if (found.what == LENGTH_NEED) { /* (bytes to come: not waited for across a record that is a frame) */
            if (final || !crosses_framed_record(L, j, -1, n)) return final ? 0 : -1;
            continue;
        }
        Py_ssize_t length = found.value;
        if (length < MIN_ADU || length > MAX_COUNTED) continue;
        if (j + length > n) {
            if (final || crosses_framed_record(L, j, length, n)) continue;
            return -1;
        }
        if (crc_ok(L->b, j, length)) return 1;
    }
    return undecided ? -1 : 0;
}

/* RtuFramer._followed, not final: a record's end (a silence) or an intact frame at `end`, or after a few glitch
 * bytes. 1 yes, 0 no, -1 more bytes needed. */
static int followed(const Line *L, Py_ssize_t end, Py_ssize_t n) {
    for (Py_ssize_t j = end;; j++) {
        if (line_bound(L, j)) return 1;
        int found = valid_frame_at(L, j, n, 0, 1);
        if (found != 0) return found;
        if (!(j < n && glitch_bytes[L->b[j]] && j - end < GLITCH_SKIP)) return 0;
    }
}

static int framed_inside(const Line *L, Py_ssize_t i, Py_ssize_t length); /* (_noise.h) */

/* RtuFramer._scan: the shortest CRC match from `minimum` bytes that an intact frame (or a record's end, a
 * silence) follows, and with a noise run open (`noise`: noise_span's) no intact frame is inside; -1: bytes to
 * come decide; 0: none (noise, the careful path's). Both of the framer's interpretations scan alike, so the first
 * one's kind stands. */
static Py_ssize_t scan_length(const Line *L, Py_ssize_t i, Py_ssize_t n, Py_ssize_t minimum, int noise) {
    Py_ssize_t reach = framed_reach(L, i, n); /* (no scan across a record that is a frame of its own) */
    Py_ssize_t maximum = reach - i < MAX_ADU ? reach - i : MAX_ADU;
    /* First a frame right after it, then one after glitch bytes (a frame and a 00 check one byte longer);
     * on a line that leaves 00 glitches, only the second (the 00 after a frame is one). */
    for (int glitches = L->glitchy ? 1 : 0; glitches < 2; glitches++) {
        CrcScan crcs = crc_scan(L->b, i, minimum, maximum);
        for (Py_ssize_t length; (length = crc_next(&crcs)) != 0;) {
            int following = glitches ? followed(L, i + length, n)
                            : line_bound(L, i + length) ? 1 : valid_frame_at(L, i + length, n, 0, 1);
            int inside = following > 0 && noise ? framed_inside(L, i, length) : 0;
            if (following < 0 || inside < 0) return -1;
            if (following && !inside) return length;
        }
    }
    /* nothing: noise; or bytes to come (none up to a record that is a frame) */
    return reach == n && n - i < MAX_ADU ? -1 : 0;
}

/* Frame length by the first interpretation (framing/rules.py _REQUEST_FIRST_FAST / _RESPONSE_FIRST_FAST);
 * *scanned: found by a CRC scan (FC8's Return Query Data), CRC and what follows checked already. */
static Py_ssize_t first_length(const Engine *e, const uint8_t *b, Py_ssize_t i, Py_ssize_t n, int function,
                               int kind, int *scanned) {
    *scanned = 0;
    if (kind == KIND_EXCEPTION) return exception_rule.fixed;
    const LengthRule *rule = &known_rule[known_slot[function]][kind == KIND_RESPONSE]; /* (a handled code: frame_kind) */
    if (rule->fixed) return rule->fixed;
    Length length = rule_length(rule, b, i, n);
    if (length.what == LENGTH_NEED) return FRAME_NEED;
    if (length.what == LENGTH_SCAN) {
        /* FC8's Return Query Data is found by the framer's own scan; FC43 other than 14 is the careful path's */
        if (!rules[handled_index(function)].special) return FRAME_HANDOVER;
        *scanned = 1;
        Py_ssize_t found = scan_length(&e->line, i, n, length.value, 0);
        return found ? found : FRAME_HANDOVER;
    }
    /* 0: the rule cannot apply; longer than any RTU frame: the careful path's (its fast path takes none) */
    return length.value == 0 || length.value > MAX_ADU ? FRAME_HANDOVER : length.value;
}

/* The kind of the frame at i on the fast path, FRAME_NEED, or FRAME_HANDOVER: none there. A frame at 00
 * is the careful path's when an intact frame follows that 00 (rules.py GLITCH_ADDRESSES: a glitch), and
 * always in a chunked stream (_match weighs it). */
static inline int frame_kind(const Engine *e, const uint8_t *b, Py_ssize_t i, Py_ssize_t n) {
    if (n - i < MIN_ADU) return FRAME_NEED;
    int slave = b[i], function = b[i + 1];
    if (slave > MAX_SLAVE) return FRAME_HANDOVER;
    if (slave == 0) {
        int after = e->tl.active ? 1 : valid_frame_at(&e->line, i + 1, n, 0, 1);
        if (after < 0) return FRAME_NEED;
        if (after) return FRAME_HANDOVER;
    }
    if (function & 0x80) {
        /* An exception: taken on the fast path only as the answer awaited (framing/rtu.py _run). */
        if (slave != e->line.expect_slave || (function & 0x7F) != e->line.expect_function) return FRAME_HANDOVER;
        return KIND_EXCEPTION;
    }
    if (handled_index(function) < 0) return FRAME_HANDOVER;
    return (slave == e->line.expect_slave && function == e->line.expect_function) ? KIND_RESPONSE : KIND_REQUEST;
}

#include "_timedframe.h" /* the framer's decision on a chunked, timed stream */

/* The frame at i (*f: its kind, slave, function, length; its time with run_timed()'s chunks), FRAME_NEED
 * or FRAME_HANDOVER: the framer's fast path (framing/rtu.py _run) on an untimed stream, its decision with
 * the chunks it had on a timed one (timed_frame, `decided`: its buffer end when it took the frame before). */
static int next_frame(Engine *e, const uint8_t *b, Py_ssize_t i, Py_ssize_t n, FrameRef *f, long long decided) {
    int kind = frame_kind(e, b, i, n), scanned;
    if (kind < 0) return kind;
    *f = (FrameRef){i, 0, kind, b[i], b[i + 1], 0, 0, 0, 0, 0, 0}; /* untimed */
    if (e->tl.active) return timed_frame(e, b, n, f, decided);
    f->length = f->tail_chars = first_length(e, b, i, n, f->function, kind, &scanned);
    if (f->length < 0 || scanned) return f->length < 0 ? (int)f->length : FRAME_OK;
    /* The Python fast path needs the byte after the frame, and takes the careful path on a 00. */
    if (i + f->length >= n) return FRAME_NEED;
    return b[i + f->length] == 0 || !crc_ok(b, i, f->length) ? FRAME_HANDOVER : FRAME_OK;
}

#include "_noise.h" /* noise framed in C where the framer's noise run is open (fastsummary.PythonSide) */

/* ---- registers ---------------------------------------------------------------------------------- */
typedef struct {
    unsigned start;        /* first address; addresses wrap at 65536 as fields.lifter's register blocks do */
    unsigned count;
    const uint8_t *values; /* big-endian words */
} Words;

static inline unsigned words_address(const Words *w, unsigned k) { return (w->start + k) & 0xFFFF; }
static inline unsigned words_value(const Words *w, unsigned k) { return word(w->values + 2 * k); }

/* The value the annotator's parameter memory (its `seen` dict) keeps for `key`, in *value (borrowed; None:
 * unreadable): 1, 0 none kept, -1 error. */
static int memory_value(Slave *s, PyObject *key, PyObject **value) {
    PyObject *last = s->seen != NULL ? PyDict_GetItemWithError(s->seen, key) : NULL;
    if (last == NULL) return PyErr_Occurred() ? -1 : 0;
    if (!PyTuple_Check(last) || PyTuple_GET_SIZE(last) < 1) return bad_info("parameter memory entry not a tuple");
    *value = PyTuple_GET_ITEM(last, 0);
    return 1;
}

static int depend_is_plain(Slave *s, unsigned address) {
    PyObject *key = PyLong_FromUnsignedLong(address);
    if (key == NULL) return -1;
    PyObject *rule = PyDict_GetItemWithError(s->depend, key);
    Py_DECREF(key);
    if (rule == NULL) return PyErr_Occurred() ? -1 : 1;
    if (!PyTuple_Check(rule) || PyTuple_GET_SIZE(rule) != 2) return bad_info("bits_depend rule not (on, values)");
    PyObject *last;
    int found = memory_value(s, PyTuple_GET_ITEM(rule, 0), &last);
    if (found <= 0) return found < 0 ? -1 : 1;
    int plain = PySet_Contains(PyTuple_GET_ITEM(rule, 1), last);
    return plain < 0 ? -1 : !plain;
}

/* 1: the annotator would give this register a plain text without a note; 0: hand over; -1: error.
 * A bits_depend answer holds for a whole run(): the engine never writes the values rules depend on
 * (it hands such transactions over), and the Python stages run only between two run() calls. */
static int register_is_plain(Slave *s, unsigned long run_number, unsigned address) {
    if (bit(s->sources, address)) return 0; /* a value others depend on: ordering matters, Python */
    if (!bit(s->dependent, address)) return 1;
    if (s->depend_run == run_number && s->depend_address == address) return s->depend_plain;
    int plain = depend_is_plain(s, address);
    if (plain >= 0) {
        s->depend_run = run_number;
        s->depend_address = address;
        s->depend_plain = plain;
    }
    return plain;
}

static int words_are_plain(Slave *s, unsigned long run_number, const Words *w) {
    for (unsigned k = 0; k < w->count; k++) {
        int plain = register_is_plain(s, run_number, words_address(w, k));
        if (plain <= 0) return plain;
    }
    return 1;
}

/* Reads as the annotator sees them: 16#8000 in a multi-word read, or a parameter unreadable before,
 * gives a note (Python's). `written`: the window this transaction wrote first (FC23; else empty), whose
 * addresses wrap at 65536 as the reads' do. */
static int reads_are_quiet(Slave *s, const Words *w, const Words *written) {
    if (s->protected_value < 0) return 1;
    for (unsigned k = 0; k < w->count; k++) {
        unsigned address = words_address(w, k);
        if (w->count > 1 && (long)words_value(w, k) == s->protected_value) return 0;
        if (s->seen == NULL || bit(s->pending, address)) continue; /* the engine's entries hold values */
        if (((address - written->start) & 0xFFFF) < written->count) continue;
        PyObject *key = PyLong_FromUnsignedLong(address), *last;
        int found = key != NULL ? memory_value(s, key, &last) : -1;
        Py_XDECREF(key);
        if (found < 0) return -1;
        if (found && last == Py_None) return 0;
    }
    return 1;
}

/* seen[address] = (value, frame number, "read" or "written"), as the annotator keeps it; logged here
 * and written to the dict by write_memory(). */
static int remember(Engine *e, int slave, Slave *s, const Words *w, unsigned long long number, int written) {
    if (grow(&e->log, &e->log_cap, e->log_len + w->count, sizeof *e->log, 4096) < 0) return -1;
    for (unsigned k = 0; k < w->count; k++) {
        unsigned address = words_address(w, k);
        e->log[e->log_len++] = (Remembered){number, (uint16_t)address, (uint16_t)words_value(w, k),
                                            (uint8_t)slave, (uint8_t)written};
        s->pending[address >> 3] |= (uint8_t)(1 << (address & 7));
    }
    return 0;
}

/* The log into the annotator's dicts, newest entry of each address only. */
static int write_memory(Engine *e) {
    int status = 0;
    for (size_t k = e->log_len; k-- > 0;) {
        const Remembered *entry = &e->log[k];
        Slave *s = &e->slaves[entry->slave];
        if (!bit(s->pending, entry->address)) continue; /* a newer entry was written already */
        s->pending[entry->address >> 3] &= (uint8_t)~(1 << (entry->address & 7));
        if (status < 0) continue;
        PyObject *how = entry->written ? e->written_word : e->read_word;
        if (dict_put(s->seen, PyLong_FromUnsignedLong(entry->address),
                     Py_BuildValue("(IKO)", (unsigned)entry->value, entry->number, how)) < 0)
            status = -1;
    }
    e->log_len = 0;
    return status;
}

static const DenseKind PIECE_KIND = {sizeof(PieceSlot), sizeof(uint64_t), 3072, key_hash};

static void pieces_clear(Engine *e) {
    for (size_t k = 0; k < e->pieces.count; k++) Py_DECREF(((PieceSlot *)e->pieces.items)[k].text);
    dense_clear(&e->pieces);
}

/* The cached text of a mapped register, asked of the Python callback on first sight. */
static const PieceSlot *piece_for(Engine *e, int slave, int function, unsigned address, unsigned value,
                                  PieceSlot *scratch) {
    /* The function matters only for a PLC-style label; it is part of the key all the same. */
    uint64_t key = (uint64_t)handled_index(function) << 40 | (uint64_t)slave << 32 | (uint64_t)address << 16 | value;
    PieceSlot *slot = dense_find(&e->pieces, &PIECE_KIND, &key);
    if (slot != NULL) return slot;
    PyObject *entry = PyObject_CallFunction(e->piece, "iiII", slave, function, address, value);
    if (entry == NULL) return NULL;
    if (!PyTuple_Check(entry) || PyTuple_GET_SIZE(entry) != 2 || !PyUnicode_Check(PyTuple_GET_ITEM(entry, 0))) {
        Py_DECREF(entry);
        PyErr_SetString(PyExc_TypeError, "piece must return (str, bool)");
        return NULL;
    }
    PieceSlot found = {key, PyTuple_GET_ITEM(entry, 0), NULL, 0, PyObject_IsTrue(PyTuple_GET_ITEM(entry, 1))};
    found.utf8 = found.named < 0 ? NULL : PyUnicode_AsUTF8AndSize(found.text, &found.length);
    if (found.utf8 == NULL) {
        Py_DECREF(entry);
        return NULL;
    }
    Py_INCREF(found.text); /* the text outlives the tuple */
    Py_DECREF(entry);
    /* (the cache full: in scratch, whose text the caller releases after use) */
    slot = e->pieces.count < PIECES ? dense_add(&e->pieces, &PIECE_KIND, &key, PIECES) : scratch;
    if (slot == NULL) Py_DECREF(found.text); /* (no memory) */
    else *slot = found;
    return slot;
}

/* `CHCF=IO (I/O profile)` or `8401=3`; *named: the annotator gave it a code or a text. */
static int piece(Engine *e, Slave *s, int slave, int function, unsigned address, unsigned value, int *named) {
    if (!bit(s->mapped, address)) {
        *named = 0;
        out_label(&e->out, s->base[handled_index(function)], address);
        out_put(&e->out, "=", 1);
        out_uint(&e->out, value, 0);
        return 0;
    }
    PieceSlot scratch = {0};
    const PieceSlot *found = piece_for(e, slave, function, address, value, &scratch);
    if (found == NULL) return -1;
    *named = found->named;
    out_put(&e->out, found->utf8, (size_t)found->length);
    Py_XDECREF(scratch.text);
    return e->out.failed ? -1 : 0;
}

/* describe.values_text */
static int values_text(Engine *e, Slave *s, int slave, int function, const Words *w) {
    int named;
    unsigned shown = w->count < MAX_VALUES ? w->count : MAX_VALUES;
    for (unsigned k = 0; k < shown; k++) {
        if (k) out_put(&e->out, " ", 1);
        if (piece(e, s, slave, function, words_address(w, k), words_value(w, k), &named) < 0) return -1;
    }
    out_more(&e->out, w->count, MAX_VALUES, " ", ")");
    return 0;
}

/* describe.span_text: `8400..8402 (3)` or `9001`; `40001..40016 (16)` PLC style (base >= 0). (A window past
 * 65535, `65535..65539 (5)`, draws the warning `span`: handed over, never written here.) */
static void span_text(Out *o, long long base, unsigned start, unsigned quantity) {
    out_label(o, base, start);
    if (quantity == 1) return;
    out_put(o, "..", 2);
    out_label(o, base, start + quantity - 1);
    out_put(o, " (", 2);
    out_uint(o, quantity, 0);
    out_put(o, ")", 1);
}

/* The registers an answer confirms written (data/modbus.toml [confirm]): its own echo (FC6), or the
 * request's values `writes` (NULL: none) a normal answer confirms (FC16, FC23); 1: some, in *out. */
static int confirmed_writes(const uint8_t *answer, const Words *writes, Words *out) {
    int k = handled_index(answer[1]);
    const Lift *L = &response_lift[k];
    if (rules[k].confirm == CONFIRM_ECHO && L->values == VALUES_ONE) {
        *out = (Words){word(answer + L->start_at), 1, answer + L->values_at};
        return 1;
    }
    if (rules[k].confirm == CONFIRM_ANSWER && writes != NULL) {
        *out = *writes;
        return 1;
    }
    return 0;
}

/* A frame as its lifting rule reads it (lift_frame). */
typedef struct {
    unsigned start, quantity; /* its window (FC23: the read part) */
    Words values;             /* the registers it carries (written, echoed or read); values.values NULL: none */
    const uint8_t *bits;      /* its coils or inputs, packed as on the wire; NULL: none */
    const uint8_t *frame;     /* its bytes: what an answer's echo fields are compared with */
    Py_ssize_t length;        /* the frame's, CRC included */
} Lifted;

#include "_stats.h"
#include "_columns.h" /* --report's pixel columns of a series */
#include "_report.h"  /* --report fed by the engine */

/* ---- one transaction ---------------------------------------------------------------------------- */
/* The spec's name of an FC8 sub-function, NULL: not defined by the spec. */
static const char *subfunction_name(unsigned sub) { return sub < SUBFUNCTIONS ? subfunction_names[sub] : NULL; }

/* fields._diagnostics and the annotator's _diagnostics say nothing of an FC8 frame: a sub-function
 * the spec defines, whole words of data, no meaning on this device, for a request the data word that
 * says nothing more (diagnostic_quiet: fields._diagnostic_data), for an answer (its `request` given) its request's
 * data where it repeats them (diagnostic_echo: fields._diagnostics). 1 quiet, 0 hand over. */
static int diagnostics_are_plain(const Slave *s, const uint8_t *f, Py_ssize_t length, const Lifted *request) {
    unsigned sub = word(f + 2);
    if ((length - 6) & 1 || bit(s->explained, sub) || subfunction_name(sub) == NULL) return 0;
    if (request != NULL)
        return !diagnostic_echo[sub]
               || (request->length == length && memcmp(request->frame + 4, f + 4, (size_t)(length - 6)) == 0);
    long quiet = diagnostic_quiet[sub];
    return quiet == DIAG_ANY || (length == 8 && (long)word(f + 4) == quiet);
}

/* describe.bits_text: the first 32 bits as 0/1, then `… (+n)` */
static void bits_text(Out *o, const uint8_t *packed, unsigned count) {
    unsigned shown = count < MAX_BITS ? count : MAX_BITS;
    if (out_reserve(o, shown) < 0) return;
    for (unsigned k = 0; k < shown; k++) o->data[o->len++] = (char)('0' + (packed[k >> 3] >> (k & 7) & 1));
    out_more(o, count, MAX_BITS, "", ")");
}

/* fields.lifter's checks of a frame by its lifting rule L (_tables.h Lift), FC8's by its named case, the
 * request it answers given (NULL for a request), and its window and data in *out: 1 it passes them all, 0 a
 * check draws a warning or a note (hand over). */
static int lift_frame(const Slave *s, const uint8_t *f, Py_ssize_t length, const Lift *L, const Lifted *request,
                      Lifted *out) {
    *out = (Lifted){0, 1, {0, 0, NULL}, NULL, f, length};
    if (L->special) return diagnostics_are_plain(s, f, length, request);
    out->start = L->start_at ? word(f + L->start_at) : request != NULL ? request->start : 0;
    out->quantity = L->quantity_at ? word(f + L->quantity_at) : L->quantity || request == NULL ? (unsigned)L->quantity
                                                                                               : request->quantity;
    for (int j = 0; j < 2 && L->check_at[j]; j++) {
        const long *range = spec_limits[L->check_limit[j]];
        long value = (long)field(f, L->check_at[j], L->check_width[j]);
        if (value > range[1] || (!L->check_above[j] && value < range[0])) return 0;
    }
    if (L->span && out->start + out->quantity > 0x10000) return 0;
    if (L->span && L->write_quantity_at && word(f + L->write_start_at) + word(f + L->write_quantity_at) > 0x10000)
        return 0; /* (FC23: its written window too) */
    if (L->count_at) {
        unsigned count = field(f, L->count_at, L->count_width);
        if (count < (unsigned)L->min_count) return 0; /* malformed: the fixed fields after it are longer */
        if (L->count_rule) {
            unsigned of = L->count_of_at ? word(f + L->count_of_at) : request->quantity;
            if (count != L->count_plus + (L->count_unit ? of * L->count_unit : (of + 7) / 8)) return 0;
            if (L->padding && (of & 7) && f[L->values_at + count - 1] >> (of & 7)) return 0; /* padding bits set */
        }
        if (L->odd_count && count & 1) return 0;
    }
    if (L->coil_at && word(f + L->coil_at) != COIL_ON && word(f + L->coil_at) != COIL_OFF) return 0;
    for (int j = 0; j < MAX_ECHO && L->echo_at[j]; j++)
        if (word(f + L->echo_at[j]) != word(request->frame + L->echo_request_at[j])) return 0;
    if (L->values == VALUES_BITS) out->bits = f + L->values_at;
    if (L->values == VALUES_BLOCK || L->values == VALUES_ONE)
        out->values = (Words){L->write_start_at ? word(f + L->write_start_at) : out->start,
                              L->values == VALUES_ONE     ? 1
                              : L->write_quantity_at ? word(f + L->write_quantity_at)
                                                     : out->quantity,
                              f + L->values_at};
    return 1;
}

/* A write request (its values, FC6/16/23; FC22's address) of a read-only parameter: access.check_writes warns
 * it (Python's). */
static int writes_read_only(const Slave *s, const uint8_t *f, int k, const Lifted *lifted) {
    if (rules[k].confirm == CONFIRM_MASK) return bit(s->read_only, word(f + 2));
    for (unsigned j = 0; j < lifted->values.count; j++)
        if (bit(s->read_only, words_address(&lifted->values, j))) return 1;
    return 0;
}

/* The decoder's and the annotator's checks of a frame (a handled code: frame_kind) by its lifting rule
 * (lift_frame), the `request` it answers given (NULL: f is a request, held to the device's quantity limits,
 * checks.within_limits; their second: FC23's written window); its window and data in *out, the registers
 * an answer reads (FC3, FC4, FC23) in *reads; its registers plain, its reads quiet. 1 quiet, 0 hand over,
 * -1 error. (Not an answer to a code of table.Compiled.texts: transaction() gives those to texts_lines.) */
static int frame_is_quiet(Engine *e, Slave *s, const uint8_t *f, Py_ssize_t length, const Lifted *request,
                          Lifted *out, Words *reads) {
    int k = handled_index(f[1]), check = s->check[k];
    const Lift *L = request != NULL ? &response_lift[k] : &request_lift[k];
    *reads = (Words){0, 0, NULL};
    if (!lift_frame(s, f, length, L, request, out)) return 0;
    /* A mask write sets a followed parameter from the value held (memory.remember_mask), and --stats and
     * --report count it with that value (history.History._mask): Python's (count_transaction counts a slave's
     * that follows none) */
    if (rules[k].confirm == CONFIRM_MASK && s->seen != NULL) return 0;
    if (request == NULL && (check < 0 || (check >= 1 && (long)out->quantity > s->limit[k][0]) ||
                            (check == 2 && (!L->write_quantity_at || (long)out->values.count > s->limit[k][1]))))
        return 0;
    if (request == NULL && writes_read_only(s, f, k, out)) return 0;
    int plain = words_are_plain(s, e->run_number, &out->values);
    if (plain <= 0 || request == NULL || L->values != VALUES_BLOCK) return plain;
    *reads = out->values;
    return rules[k].reads ? reads_are_quiet(s, reads, &request->values) : 1;
}

/* The Info column by its describer's form (info->steps: those of form_steps, _tables.h, generated from
 * codegen/c_rules.py's TEXT_FORMS), from the fields it prints (at info->at, info->width bytes) and the
 * frame as lifted (its window, bits, registers): 1 written, 0 a form this engine does not write or a text
 * Python's str.rstrip() in info_text would change (not ending in a plain visible character), -1 error. */
static int info_text(Engine *e, Slave *s, const InfoForm *info, const Lifted *lifted) {
    const uint8_t *f = lifted->frame;
    int slave = f[0], function = f[1];
    long long base = s->base[handled_index(function)];
    unsigned start = lifted->start, quantity = lifted->quantity;
    for (const Step *step = info->steps; step->step != STEP_END; step++) {
        unsigned value = step->field >= 0 ? field(f, info->at[step->field], info->width[step->field]) : 0;
        switch (step->step) {
        case STEP_NONE:
            return 0;
        case STEP_TEXT:
            out_put(&e->out, step->text, (size_t)step->length);
            break;
        case STEP_UNSPACE: /* describe.TEXT_FORMS' name: the name alone */
            e->out.len -= 1;
            break;
        case STEP_SPAN: /* PLAIN_SPAN: describe._plain_span, FC23's read part: the same text (PLC style too) */
        case STEP_PLAIN_SPAN:
            span_text(&e->out, base, start, quantity);
            break;
        case STEP_LABEL:
            out_label(&e->out, base, start);
            break;
        case STEP_BITS:
            bits_text(&e->out, lifted->bits, quantity);
            break;
        case STEP_WRITE: /* describe._step write: FC23 writing none (its quantity 0 warned) is Python's */
            if (lifted->values.count == 0) return 0;
            /* fall through */
        case STEP_VALUES:
            if (values_text(e, s, slave, function, &lifted->values) < 0) return -1;
            break;
        case STEP_COIL:
            out_cstr(&e->out, value == COIL_ON ? " = ON" : " = OFF");
            break;
        case STEP_SINGLE: { /* describe._single: ` HSP=50.9 Hz` when named, ` = 7` otherwise */
            size_t mark = e->out.len;
            int named;
            out_put(&e->out, " ", 1);
            if (piece(e, s, slave, function, start, value, &named) < 0) return -1;
            if (!named) {
                e->out.len = mark;
                out_put(&e->out, " = ", 3);
                out_uint(&e->out, value, 0);
            }
            break;
        }
        case STEP_DEC:
            out_uint(&e->out, value, 0);
            break;
        case STEP_COUNT: /* describe.count_text: `1 event`, `2 events` (the noun in step->text) */
            out_uint(&e->out, value, 0);
            out_put(&e->out, " ", 1);
            out_put(&e->out, step->text, (size_t)step->length);
            if (value != 1) out_put(&e->out, "s", 1);
            break;
        case STEP_HEX:
            out_number(&e->out, value, 16, step->number, '0');
            break;
        case STEP_SUBFUNCTION: /* diagnostics_are_plain: the spec names it */
            out_cstr(&e->out, subfunction_name(value));
            break;
        case STEP_DATA: { /* describe._data: the data up to the CRC, ` = 7` for a word, else its first bytes */
            const uint8_t *data = f + info->at[step->field];
            Py_ssize_t size = f + lifted->length - 2 - data, shown = size < MAX_DATA_BYTES ? size : MAX_DATA_BYTES;
            if (size == 2) {
                out_put(&e->out, " = ", 3);
                out_uint(&e->out, word(data), 0);
                break;
            }
            if (size > 0) out_cstr(&e->out, " data ");
            if (out_reserve(&e->out, (size_t)(2 * shown)) < 0) return -1;
            for (Py_ssize_t k = 0; k < shown; k++) {
                e->out.data[e->out.len++] = "0123456789abcdef"[data[k] >> 4];
                e->out.data[e->out.len++] = "0123456789abcdef"[data[k] & 15];
            }
            if (size > 0) out_more(&e->out, (unsigned long long)size, MAX_DATA_BYTES, "", " bytes)");
            break;
        }
        case STEP_FIFO: /* describe._fifo: `:` and the first of `value` words, how many more; nothing for none */
            if (value > 0) out_put(&e->out, ":", 1);
            for (unsigned j = 0; j < value && j < MAX_FIFO_VALUES; j++) {
                out_put(&e->out, " ", 1);
                out_uint(&e->out, word(f + info->at[step->number] + 2 * j), 0);
            }
            out_more(&e->out, value, MAX_FIFO_VALUES, " ", ")");
            break;
        }
    }
    if (e->out.failed) return -1;
    unsigned char last = (unsigned char)e->out.data[e->out.len - 1];
    return last > 0x20 && last < 0x7F;
}

/* The line `number` of frame f: summary.summary_line's head (number, time (`-`: untimed), slave, kind), its
 * info, ` [no response]` (`unanswered`), for an answer the pairing with its `request` (the line before;
 * NULL: f is a request), the tail, the CRC. The info is written from the frame as `lifted` (after the
 * slave's function name) or, with `lifted` NULL, is the Python stages' `info`, with their `tail` (NULL:
 * none). 1 written, 0 hand over, -1 error. */
static int line(Engine *e, const FrameRef *f, const FrameRef *request, unsigned long long number, int unanswered,
                Slave *s, const Lifted *lifted, PyObject *info, PyObject *tail) {
    out_uint(&e->out, number, 6);
    out_time_column(&e->out, &e->tl, f->timed, f->ns, f->before);
    out_uint(&e->out, (unsigned)f->slave, 3);
    out_cstr(&e->out, kind_column[f->kind]);
    int k = handled_index(f->function & 0x7F);
    if (out_str(&e->out, lifted != NULL ? s->name[k] : info) < 0) return -1; /* (refuses a text not a str) */
    if (lifted != NULL) {
        out_put(&e->out, " ", 1);
        int written = info_text(e, s, &rules[k].info[request != NULL], lifted);
        if (written <= 0) return written;
    }
    if (unanswered) out_cstr(&e->out, " [no response]");
    if (request != NULL) {
        out_put(&e->out, " ", 1);
        out_pairing(&e->out, number - 1, request->timed && f->timed, request->ns, f->ns);
    }
    if (tail != NULL && out_str(&e->out, tail) < 0) return -1;
    out_cstr(&e->out, "  CRC ok\n");
    return e->out.failed ? -1 : 1;
}

/* A transaction whose texts come from the Python stages (fastsummary.transaction_texts: a code of
 * table.Compiled.texts, or an exception): the request and its answer (NULL: unanswered). 1 written, 0
 * hand over, -1 error. */
static int texts_lines(Engine *e, const FrameRef *q, const uint8_t *b, const FrameRef *a, unsigned long long number) {
    if (e->texts == NULL || e->texts == Py_None) return 0;
    PyObject *answer = a != NULL ? PyBytes_FromStringAndSize((const char *)b + a->at, a->length) : Py_NewRef(Py_None);
    PyObject *texts = PyObject_CallFunction(e->texts, "iy#N", q->slave, (const char *)b + q->at, q->length, answer);
    if (texts == NULL) return -1;
    if (texts == Py_None) {
        Py_DECREF(texts);
        return 0;
    }
    static PyObject *keys[TEXTS];
    PyObject *item = read_fields(texts, text_names, keys, TEXTS, "texts (a fastsummary.Texts)");
    Py_DECREF(texts);
    if (item == NULL) return -1;
    int status = line(e, q, NULL, number, a == NULL, NULL, NULL, PyTuple_GET_ITEM(item, TEXT_REQUEST_INFO),
                      PyTuple_GET_ITEM(item, TEXT_REQUEST_TAIL));
    if (status > 0 && a != NULL)
        status = line(e, a, q, number + 1, 0, NULL, NULL, PyTuple_GET_ITEM(item, TEXT_RESPONSE_INFO),
                      PyTuple_GET_ITEM(item, TEXT_RESPONSE_TAIL));
    Py_DECREF(item);
    return status;
}

/* Annotator state after an answered transaction: what was written, then what was read. */
static int track(Engine *e, Slave *s, const uint8_t *f, const Words *writes, const Words *reads,
                 unsigned long long number) {
    if (s->seen == NULL) return 0;
    Words written;
    if (confirmed_writes(f, writes, &written) && remember(e, f[0], s, &written, number, 1) < 0) return -1;
    if (reads->count && s->protected_value >= 0) return remember(e, f[0], s, reads, number, 0);
    return 0;
}

/* ---- the Python object ------------------------------------------------------------------------- */
enum { STEP_DONE, STEP_NEED, STEP_HANDOVER, STEP_ERROR };

/* A transaction's lines are written (or its record, _judge.h): its frames are numbered, the stream moves
 * past its answer, or up to `a`, the next request, when it was not answered. */
static int taken(Engine *e, Py_ssize_t *pos, const FrameRef *q, const FrameRef *a, int answered) {
    e->count += answered ? 2 : 1;
    if (answered) e->line.expect_slave = e->line.expect_function = -1;
    *pos = answered ? a->at + a->length : a->at;
    e->tl.decided = answered ? a->decided : q->decided;
    return STEP_DONE;
}

/* A request the spec has no server answer ([pairing] never_answered: FC8 04 Force Listen Only Mode): a note
 * of pairing.py's, the Python stages'. */
static int never_answered_request(const uint8_t *f, Py_ssize_t length) {
    for (int k = 0; k < NEVER_ANSWERED; k++)
        if (f[1] == never_answered[k][0] && length >= 6 && word(f + 2) == never_answered[k][1]) return 1;
    return 0;
}

/* Does answer a repeat of request q what the spec has it echo ([pairing] echo: FC8's sub-function), both
 * holding it whole? Otherwise the Python stages decide (answer_to hands over): pairing.py _echoes weighs the
 * bytes of it both hold. */
static int echoes(const uint8_t *b, const FrameRef *q, const FrameRef *a) {
    for (int k = 0; k < ECHOES; k++) {
        Py_ssize_t count = answer_echo[k][1];
        if (q->function == answer_echo[k][0])
            return a->kind != KIND_RESPONSE ||
                   (q->length >= 4 + count && a->length >= 4 + count && !memcmp(b + q->at + 2, b + a->at + 2, count));
    }
    return 1;
}

/* The frame after request q, expected as its answer: FRAME_OK (in *a: its answer, or the next request when
 * it was not answered), FRAME_NEED, or FRAME_HANDOVER, an answer later than the timeout after q was sent
 * (frame_sent) too (no answer:
 * pairing.py's warning), stamped before q (time going backwards: pairing.py's warning) or not echoing q (an
 * answer to nothing: pairing.py's note). A caller that
 * does not take the transaction takes the expectation back. */
static int answer_to(Engine *e, const uint8_t *b, Py_ssize_t n, const FrameRef *q, FrameRef *a) {
    e->line.expect_slave = q->slave;
    e->line.expect_function = q->function;
    int found = next_frame(e, b, q->at + q->length, n, a, q->decided);
    if (found == FRAME_OK && a->kind != KIND_REQUEST &&
        ((q->timed && a->timed && (a->ns < q->ns || (e->tl.timeout >= 0 &&
          stamp_seconds(a->ns, q->ns) - frame_sent(q, e->tl.char_time) > e->tl.timeout)))
         || !echoes(b, q, a)))
        return FRAME_HANDOVER;
    return found;
}

#include "_judge.h" /* profile auto's first pass: frames and pairs only */

/* One transaction from *pos: shown (STEP_DONE, *pos moves past it) or left as it was found. */
static int transaction(Engine *e, const uint8_t *b, Py_ssize_t n, Py_ssize_t *pos) {
    FrameRef q, a;
    int found = next_frame(e, b, *pos, n, &q, e->tl.decided);
    if (found != FRAME_OK) return found == FRAME_NEED ? STEP_NEED : STEP_HANDOVER;
    /* (a broadcast, a request no answer follows: awaiting nothing, pairing.py's) */
    if (q.kind != KIND_REQUEST || q.slave == 0 || never_answered_request(b + q.at, q.length) ||
        (e->judge != NULL && judged(e, &q)))
        return STEP_HANDOVER;
    Slave *s = NULL;
    Lifted r, answer;
    Words reads = {0, 0, NULL};
    if (e->judge == NULL) { /* (judged: framed and paired only) */
        s = &e->slaves[q.slave];
        if (!s->loaded && load_slave(e, q.slave) < 0) return STEP_ERROR;
        if (!s->usable) return STEP_HANDOVER;
        int quiet = frame_is_quiet(e, s, b + q.at, q.length, NULL, &r, &reads);
        if (quiet <= 0) return quiet < 0 ? STEP_ERROR : STEP_HANDOVER;
    }
    int saved_slave = e->line.expect_slave, saved_function = e->line.expect_function;
    size_t mark = e->out.len;
    found = answer_to(e, b, n, &q, &a);
    ClockRefs clock = e->tl.refs; /* the time column's references, taken back with the lines */
    /* The next frame is a request: this one was not answered (pairing.py). */
    int answered = found == FRAME_OK && a.kind != KIND_REQUEST, written = 0;
    const Words *writes = s != NULL && r.values.values != NULL ? &r.values : NULL; /* (s: not judged) */
    if (e->judge != NULL) {
        written = found == FRAME_OK && (!answered || !judged(e, &a)) ? frames_record(e, &q, answered ? &a : NULL) : 0;
    } else if (found == FRAME_OK && rules[handled_index(q.function)].texts != (answered && a.kind == KIND_EXCEPTION)) {
        /* Texts from the Python stages: a code of table.Compiled.texts (not its exceptions), an exception */
        written = texts_lines(e, &q, b, answered ? &a : NULL, e->count + 1);
    } else if (found == FRAME_OK && (!answered || a.kind == KIND_RESPONSE)) {
        /* (not an exception to a code of table.Compiled.texts: the Python stages') */
        written = answered ? frame_is_quiet(e, s, b + a.at, a.length, &r, &answer, &reads) : 1;
        if (written > 0) written = line(e, &q, NULL, e->count + 1, !answered, s, &r, NULL, NULL);
        if (written > 0 && answered) {
            written = line(e, &a, &q, e->count + 2, 0, s, &answer, NULL, NULL);
            if (written > 0 && track(e, s, b + a.at, writes, &reads, e->count + 2) < 0) written = -1;
        }
    }
    /* --stats: the transaction's counts once its lines are written (_stats.h) */
    if (written > 0 && s != NULL && e->stats != NULL &&
        count_transaction((Stats *)e->stats, s, b, &q, answered ? &a : NULL, &r, &reads, e->count + 1,
                          e->tl.active ? e->tl.base : 0) < 0)
        written = -1;
    if (written > 0) return taken(e, pos, &q, &a, answered);
    /* Not shown here: its lines and its expectation are taken back. */
    e->out.len = mark;
    e->out.failed = 0;
    e->line.expect_slave = saved_slave;
    e->line.expect_function = saved_function;
    e->tl.refs = clock;
    return written < 0 ? STEP_ERROR : found == FRAME_NEED ? STEP_NEED : STEP_HANDOVER;
}

/* 1, or 0 with RuntimeError inside run() (`what` the call refused): a callback calling back in would
 * change or free what the outer call uses. */
static int idle(const Engine *e, const char *what) {
    if (e->running) PyErr_Format(PyExc_RuntimeError, "%s: not inside run()", what);
    return !e->running;
}

/* run(buffer, position) -> (lines, position, status): the transactions of buffer from position on;
 * run_timed(buffer, position, base, starts, times, flags[, befores]): the same on a stream of chunks (_timeline.h):
 * `base` the stream offset of buffer[0]; per chunk its start (stream offset, int64), its time (int64 ns)
 * and its flags (a byte), and for CLOCK_PACKETS the time of the packet before it (int64 ns, NO_BEFORE: none);
 * the first chunk holds buffer[0], the last one ends with the buffer. */
static PyObject *engine_run(Engine *e, PyObject *args) {
    Py_buffer view, starts = {0}, times = {0}, flags = {0}, befores = {0};
    Py_ssize_t pos;
    long long base = 0;
    if (e->slave_info == NULL) return PyErr_Format(PyExc_RuntimeError, "Engine not initialised");
    if (!idle(e, "run") || !PyArg_ParseTuple(args, "y*n|Ly*y*y*y*", &view, &pos, &base, &starts, &times, &flags, &befores))
        return NULL;
    int timed = PyTuple_GET_SIZE(args) > 2, step = STEP_ERROR;
    Py_ssize_t count = starts.len / (Py_ssize_t)sizeof(long long);
    const long long *start = starts.buf;
    Timeline *t = &e->tl;
    if (timed && (count < 1 || starts.len % (Py_ssize_t)sizeof(long long) || times.len != starts.len ||
                  flags.len != count || start[0] > base || start[count - 1] >= base + view.len ||
                  (befores.buf != NULL && befores.len != starts.len))) {
        PyErr_SetString(PyExc_ValueError, "run_timed: one start, time and flag per chunk, covering the buffer");
    } else if (pos < 0 || pos > view.len) {
        PyErr_SetString(PyExc_ValueError, "position outside the buffer");
    } else {
        if (timed) {
            t->active = 1;
            t->base = base;
            t->start = start;
            t->ns = times.buf;
            t->before = befores.buf; /* (NULL: none given) */
            t->flags = flags.buf;
            t->count = count;
            t->end = base + view.len;
            t->cursor = 0;
        }
        e->running = 1;
        e->run_number++;
        e->line.b = view.buf;
        e->line.size = view.len;
        e->out.len = 0;
        e->out.failed = 0;
        do {
            step = transaction(e, view.buf, view.len, &pos);
        } while (step == STEP_DONE);
        /* The Python stages may read the parameter memory as soon as this returns. */
        if (write_memory(e) < 0) step = STEP_ERROR;
        e->running = 0;
        t->active = 0;
        t->start = t->ns = t->before = NULL;
        t->flags = NULL;
    }
    PyBuffer_Release(&view);
    PyBuffer_Release(&starts);
    PyBuffer_Release(&times);
    PyBuffer_Release(&flags);
    if (befores.buf != NULL) PyBuffer_Release(&befores);
    if (step == STEP_ERROR) return NULL; /* a failing callback or no memory: a bug to see, not to hide */
    /* UTF-8 bytes: written to the binary stream as they are, with no round trip through str. */
    PyObject *lines = PyBytes_FromStringAndSize(e->out.data ? e->out.data : "", (Py_ssize_t)e->out.len);
    if (lines == NULL) return NULL;
    return Py_BuildValue("(Nni)", lines, pos, step == STEP_NEED ? STATUS_NEED : STATUS_HANDOVER);
}

/* stats and judge (at offset `closure`) are set between two runs only, to a Stats or to the judge bitmap
 * (a bit per slave and function code), or to None (NULL). */
static int engine_set_object(Engine *e, PyObject *value, void *closure) {
    int judge = (size_t)closure == offsetof(Engine, judge);
    int fits = value == NULL || value == Py_None || (judge ? PyBytes_Check(value) && PyBytes_GET_SIZE(value) == 256 * 32
                                                           : PyObject_TypeCheck(value, &StatsType));
    if (!idle(e, judge ? "judge" : "stats")) return -1;
    if (!fits)
        return fail(PyExc_TypeError, judge ? "judge: 8192 bytes (a bit per slave and function code) or None"
                                           : "stats: a Stats or None");
    PyObject **field = (PyObject **)((char *)e + (size_t)closure);
    Py_XSETREF(*field, value == Py_None ? NULL : Py_XNewRef(value));
    return 0;
}

/* The objects an engine holds: its three callbacks in engine_init's order, then what it keeps. */
#define ENGINE_HELD(e)                                                                                   \
    {&(e)->slave_info, &(e)->piece, &(e)->texts, &(e)->read_word, &(e)->written_word, &(e)->stats, &(e)->judge}

static int engine_init(Engine *e, PyObject *args, PyObject *kwargs) {
    PyObject *slave_info, *piece_fn, *texts_fn = Py_None;
    static char *keywords[] = {"slave_info", "piece", "texts", NULL};
    if (!idle(e, "Engine.__init__")) return -1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|O", keywords, &slave_info, &piece_fn, &texts_fn)) return -1;
    PyObject **held[] = ENGINE_HELD(e);
    PyObject *given[] = {slave_info, piece_fn, texts_fn};
    for (int k = 0; k < 3; k++) Py_XSETREF(*held[k], Py_NewRef(given[k]));
    pieces_clear(e);
    Py_XSETREF(e->read_word, PyUnicode_InternFromString("read"));
    Py_XSETREF(e->written_word, PyUnicode_InternFromString("written"));
    if (e->read_word == NULL || e->written_word == NULL) return -1;
    for (int k = 0; k < 256; k++) slave_clear(&e->slaves[k]);
    e->count = 0;
    e->line.expect_slave = e->line.expect_function = -1;
    e->line.tl = &e->tl;
    e->tl.timeout = -1;
    return 0;
}

static int engine_traverse(Engine *e, visitproc visit, void *arg) {
    PyObject **held[] = ENGINE_HELD(e);
    for (size_t k = 0; k < sizeof held / sizeof *held; k++) Py_VISIT(*held[k]);
    for (int k = 0; k < 256; k++) Py_VISIT(e->slaves[k].info);
    return 0;
}

static int engine_clear(Engine *e) {
    PyObject **held[] = ENGINE_HELD(e);
    clear_all(held, sizeof held / sizeof *held);
    pieces_clear(e);
    for (int k = 0; k < 256; k++) slave_clear(&e->slaves[k]);
    return 0;
}

static void engine_dealloc(Engine *e) {
    PyObject_GC_UnTrack(e);
    engine_clear(e);
    PyMem_Free(e->out.data);
    PyMem_Free(e->log);
    dense_free(&e->pieces);
    Py_TYPE(e)->tp_free((PyObject *)e);
}

/* forget(slave): ask slave_info again on the slave's next transaction (its device profile changed). */
static PyObject *engine_forget(Engine *e, PyObject *args) {
    unsigned char address; /* (PyArg's "b": OverflowError outside 0..255) */
    if (!PyArg_ParseTuple(args, "b", &address) || !idle(e, "forget")) return NULL;
    slave_clear(&e->slaves[address]);
    pieces_clear(e); /* register texts of the old profile (rare: a profile changes a few times a run) */
    Py_RETURN_NONE;
}

static PyMethodDef engine_methods[] = {
    {"forget", (PyCFunction)engine_forget, METH_VARARGS,
     "forget(slave): ask slave_info again on the slave's next transaction (its profile changed)."},
    {"run", (PyCFunction)engine_run, METH_VARARGS,
     "run(buffer, position) -> (lines, position, status): summary lines (UTF-8) of the transactions from\n"
     "position on; status 0: needs more bytes, 1: hand the stream over at position."},
    {"run_timed", (PyCFunction)engine_run, METH_VARARGS,
     "run_timed(buffer, position, base, starts, times, flags[, befores]) -> run()'s answer, for a stream of\n"
     "timed chunks (pcap records): int64 stream offsets and ns times, a flag byte per chunk, the packet before\n"
     "each's time in ns (_timeline.h)."},
    {NULL, NULL, 0, NULL},
};

static PyMemberDef engine_members[] = {
    {"count", T_ULONGLONG, offsetof(Engine, count), 0, "items numbered so far"},
    {"frames", T_BOOL, offsetof(Engine, frames), 0,
     "with judge: run() returns a record per transaction passed instead of lines (_judge.h)"},
    {"decided", T_LONGLONG, offsetof(Engine, tl.decided), 0,
     "run_timed(): the Python framer's buffer end (stream offset) when it decided the last frame"},
    {"glitchy", T_BOOL, offsetof(Engine, line.glitchy), 0,
     "the line leaves 00 glitches (the framer's glitchy): CRC scans take the shortest length"},
    /* Plain fields, in the shapes fastsummary.PathEngine gives its callers (expect, clock, set_timing). */
    {"expect_slave", T_INT, offsetof(Engine, line.expect_slave), 0, "the slave whose answer is awaited, -1: none"},
    {"expect_function", T_INT, offsetof(Engine, line.expect_function), 0, "the function code awaited"},
    {"char_time", T_DOUBLE, offsetof(Engine, tl.char_time), 0, "the line's character time, s (timing.LineTiming)"},
    {"t15", T_DOUBLE, offsetof(Engine, tl.t15), 0, "the line's t1.5, s: a longer silence inside a frame warns"},
    {"timeout", T_DOUBLE, offsetof(Engine, tl.timeout), 0, "the pairing timeout, s; < 0: none"},
    {"clock_format", T_INT, offsetof(Engine, tl.clock), 0, "the time column: 0 -t r, 1 -t d or dd"},
    {"clock_nanos", T_INT, offsetof(Engine, tl.nanos), 0, "1: the time column in ns (9 decimals), 0: in us"},
    {"has_first", T_INT, offsetof(Engine, tl.refs.has_first), 0, "the time column has its first timed item"},
    {"first_ns", T_LONGLONG, offsetof(Engine, tl.refs.first_ns), 0, "its time, ns"},
    {"has_previous", T_INT, offsetof(Engine, tl.refs.has_previous), 0, "it has a previous timed item"},
    {"previous_ns", T_LONGLONG, offsetof(Engine, tl.refs.previous_ns), 0, "its time, ns"},
    {NULL, 0, 0, 0, NULL},
};

static PyGetSetDef engine_getset[] = {
    {"stats", (getter)object_get, (setter)engine_set_object,
     "a Stats that counts every transaction shown here (--stats), or None", (void *)offsetof(Engine, stats)},
    {"judge", (getter)object_get, (setter)engine_set_object,
     "profile auto's first pass: a bit per (slave, function) whose frames go to the Python stages; no lines",
     (void *)offsetof(Engine, judge)},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyTypeObject EngineType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "dissector.accel._summary.Engine",
    .tp_basicsize = sizeof(Engine),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE | Py_TPFLAGS_HAVE_GC,
    .tp_doc = "The compiled summary path (see dissector/accel/fastsummary.py PathEngine).",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)engine_init,
    .tp_dealloc = (destructor)engine_dealloc,
    .tp_traverse = (traverseproc)engine_traverse,
    .tp_clear = (inquiry)engine_clear,
    .tp_methods = engine_methods,
    .tp_members = engine_members,
    .tp_getset = engine_getset,
};

/* crc.crc_lengths: one incremental pass instead of one CRC per candidate length. */
static PyObject *module_crc_lengths(PyObject *self, PyObject *args) {
    Py_buffer view;
    Py_ssize_t start, minimum, maximum;
    if (!PyArg_ParseTuple(args, "y*nnn", &view, &start, &minimum, &maximum)) return NULL;
    if (start < 0 || start > view.len) start = maximum = 0; /* outside the buffer: no length */
    if (start + maximum > view.len) maximum = view.len - start;
    CrcScan scan = crc_scan(view.buf, start, minimum, maximum);
    PyObject *lengths = PyList_New(0);
    for (Py_ssize_t length; lengths != NULL && (length = crc_next(&scan)) != 0;)
        if (list_put(lengths, PyLong_FromSsize_t(length)) < 0) Py_CLEAR(lengths);
    PyBuffer_Release(&view);
    return lengths;
}

static PyMethodDef module_methods[] = {
    {"scan_pcap", module_scan_pcap, METH_VARARGS,
     "scan_pcap(buffer, position, big_endian, units, offset, previous, char_time, t35, chunk_size) -> a block\n"
     "of the pcap records in buffer from position (see _records.h)."},
    {"noise_span", module_noise_span, METH_VARARGS,
     "noise_span(buffer, limit, expect_slave, expect_function, echo, glitchy, base, ends, starts) -> (how many\n"
     "bytes from the buffer's start the RTU framer, its noise run open, takes as noise; whether it waits for more\n"
     "bytes there) (see _noise.h)."},
    {"crc_lengths", module_crc_lengths, METH_VARARGS,
     "crc_lengths(buffer, start, minimum, maximum) -> the lengths L in minimum..maximum at which\n"
     "buffer[start:start + L] ends in the CRC-16/MODBUS of the bytes before it."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef summary_module = {
    PyModuleDef_HEAD_INIT, "_summary", "The compiled summary path of vw3-decode.", -1, module_methods,
};

#ifndef VW3_SOURCES
#define VW3_SOURCES ""  /* built without setup.py: never taken for the sources beside it */
#endif

PyMODINIT_FUNC PyInit__summary(void) {
    PyObject *module = PyModule_Create(&summary_module);
    PyTypeObject *types[] = {&EngineType, &StatsType, &ColumnsType, &ReportType};
    /* The stamp of the sources it was built from (dissector/accel/stamp.py, checked on import). */
    int failed = module == NULL || PyModule_AddStringConstant(module, "SOURCES", VW3_SOURCES) < 0;
    for (size_t k = 0; !failed && k < sizeof types / sizeof *types; k++) failed = PyModule_AddType(module, types[k]) < 0;
    if (failed) Py_CLEAR(module);
    return module;
}
