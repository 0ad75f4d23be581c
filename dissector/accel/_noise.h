/* Noise framed in C: how far the RTU framer (framing/rtu.py RtuFramer._run) would take its buffer as noise,
 * in the state where noise costs it most: a noise run open, no silence in its buffer, not at the end of the
 * input. There _run skips what no frame can start (_POSSIBLE_START) and weighs every other position in full
 * (_match, _scan, _followed, _intact_inside, _take_bounded at a record's start): 668,748 _match calls for 1 MB
 * of random bytes, 4 to 5 s, and more where pcap records bound the bytes. This is the same decision, position
 * by position, with the same tables (_tables.h) and the record ends and starts the framer keeps; it stops at
 * the first position whose decision is anything else (a frame with a good CRC, a damaged frame shown, a run
 * the line bounds, bytes still to come), which the framer then decides itself. accel/fastsummary.py
 * skip_noise adds the noise to the framer's run; tests/differential/test_noise_span.py holds the outputs equal
 * to the Python stages'. Included by _summary.c, after its framing helpers. */

enum { NZ_NEED = -1, NZ_NONE = 0 }; /* a length found, or these (rules.py NEED, NONE) */

/* StreamFramer._record_starts_at. */
static inline int nz_start(const Line *L, Py_ssize_t j) {
    Py_ssize_t k = lower_index(L->starts, L->start_count, j);
    return k < L->start_count && L->starts[k] == j;
}

/* The kind of interpretation r of layouts() (the exception's; the awaited answer's first, the other, the
 * request by its quantity). */
static int nz_kind(int function, int expected, int r) {
    if (function & 0x80) return KIND_EXCEPTION;
    if (r == 2) return KIND_REQUEST;
    return (r == 0) == !!expected ? KIND_RESPONSE : KIND_REQUEST;
}

/* Bounded._intact_inside: a frame with a length rule and a good CRC starts inside i..i+length. */
static int nz_intact_inside(const Line *L, Py_ssize_t i, Py_ssize_t length, Py_ssize_t n, int final) {
    int undecided = 0;
    for (Py_ssize_t j = i + 1; j < i + length; j++) {
        int found = valid_frame_at(L, j, n, final, 0);
        if (found == 1) return 1;
        undecided = undecided || found < 0;
    }
    return undecided ? -1 : 0;
}

/* Bounded._framed_inside, not final: _intact_inside up to the reading's end where records that are frames
 * bound it there. */
static int framed_inside(const Line *L, Py_ssize_t i, Py_ssize_t length) {
    Py_ssize_t end = i + length, n = L->size;
    int bounded = line_bound(L, end) && (nz_start(L, i) || (n - end >= MIN_ADU && ends_record(L, end, n)));
    return nz_intact_inside(L, i, length, bounded ? end : n, bounded);
}

/* rtu._counts_nothing: a counted layout of the code (its request's or response's) whose count is 0. */
static int nz_counts_nothing(int function, int kind, Py_ssize_t length) {
    if (function & 0x80 || kind == KIND_EXCEPTION) return 0;
    const LengthRule *rule = &known_rule[known_slot[function]][kind == KIND_RESPONSE];
    return !rule->fixed && rule->special == RULE_COUNTED && length == rule->extra;
}

/* What _run makes of a position (nz_take): noise, a decision that waits for bytes to come (_run's break), or
 * anything else (a frame with a good CRC, a damaged frame, a run the line bounds): the framer's to take. */
enum { NZ_TAKE = 0, NZ_NOISE = 1, NZ_WAIT = 2 };

/* Bounded._bounded_run from a record's start or end (a frame's end never falls inside an open noise run):
 * NZ_NOISE no run there, NZ_WAIT bytes to come, NZ_TAKE a run. */
static int nz_bounded_run(const Line *L, Py_ssize_t i) {
    if (!line_bound(L, i) && !nz_start(L, i)) return NZ_NOISE;
    Py_ssize_t n = L->size, end = line_end_after(L, i, n), stop = end >= 0 ? end : n;
    int last = end >= 0;
    for (Py_ssize_t e = i + 1; e <= (stop < i + MAX_ADU ? stop : i + MAX_ADU); e++) {
        int found = valid_frame_at(L, e, stop, last, 0);
        if (found < 0) return NZ_WAIT;
        if (found) return e - i >= MIN_ADU && crc_ok(L->b, i, e - i) ? NZ_TAKE : NZ_NOISE;
    }
    return !last && n - i < MAX_ADU ? NZ_WAIT : NZ_NOISE;
}

/* RtuFramer._match at i with a noise run open, not final: NZ_NOISE (its NONE), NZ_WAIT (NEED), NZ_TAKE (a
 * reading with a good CRC), or NZ_DAMAGED (a damaged frame it shows). */
enum { NZ_DAMAGED = 3 };
static int nz_match(const Line *L, Py_ssize_t i) {
    const uint8_t *b = L->b;
    Py_ssize_t n = L->size;
    int slave = b[i], function = b[i + 1];
    if (glitch_bytes[slave] && (slave == 0 || slave > MAX_SLAVE)) { /* rules.GLITCH_ADDRESSES */
        int after = valid_frame_at(L, i + 1, n, 0, 1);
        if (after > 0) return NZ_NOISE; /* a glitch byte before a frame */
        if (after < 0 && !ends_record(L, i, n)) return NZ_WAIT;
    }
    int expected = awaited(L, i), waiting = 0, damaged = 0;
    Py_ssize_t damaged_length[3];
    const LengthRule *rules[3];
    int count = layouts(function, expected, rules);
    for (int r = 0; r < count; r++) {
        Length found = rule_length(rules[r], b, i, n);
        if (found.what == LENGTH_SCAN) {
            Py_ssize_t length = scan_length(L, i, n, found.value, 1), declared = found.declared;
            if (length == NZ_NEED) waiting++;
            else if (length) return NZ_TAKE;
            else if (declared >= MIN_ADU && declared <= MAX_ADU && declared <= n - i) /* (rules.Scan.declared) */
                damaged_length[damaged++] = declared;
            continue;
        }
        Py_ssize_t length = found.what == LENGTH_NEED ? NZ_NEED : found.value;
        if (length != NZ_NEED && (length < MIN_ADU || length > MAX_COUNTED)) continue;
        if (length == NZ_NEED || i + length > n) {
            waiting += !crosses_framed_record(L, i, length, n);
            continue;
        }
        if (crc_ok(b, i, length)) return NZ_TAKE;
        if (length <= MAX_ADU && !nz_counts_nothing(function, nz_kind(function, expected, r), length))
            damaged_length[damaged++] = length; /* (over it: a good CRC only) */
    }
    if (waiting) return NZ_WAIT;
    if (slave > MAX_SLAVE || (slave == 0 && not_broadcast[function])) return NZ_NOISE;
    if (glitch_bytes[slave]) {
        int after = valid_frame_at(L, i + 1, n, 0, 1);
        if (after) return after > 0 ? NZ_NOISE : NZ_WAIT;
    }
    for (int k = 0; k < damaged; k++) {
        if (crosses_framed_record(L, i, damaged_length[k], n)) continue;
        int following = followed(L, i + damaged_length[k], n);
        if (following < 0) return NZ_WAIT;
        if (following) {
            int inside = framed_inside(L, i, damaged_length[k]);
            if (inside < 0) return NZ_WAIT;
            if (!inside) return NZ_DAMAGED;
        }
    }
    return NZ_NOISE;
}

/* What RtuFramer._run, a noise run open, not final, makes of position i (a known code after it): _match, then
 * where it finds no frame or a damaged one, a run the line bounds (_take_bounded) first. */
static int nz_take(const Line *L, Py_ssize_t i) {
    int match = nz_match(L, i);
    if (match == NZ_WAIT || match == NZ_TAKE) return match;
    int bounded = nz_bounded_run(L, i);
    return bounded != NZ_NOISE ? bounded : match == NZ_DAMAGED ? NZ_TAKE : NZ_NOISE;
}

/* Where RtuFramer._run, a noise run open, stops taking the bytes from `start` as noise, before `limit`; *wait:
 * it waits for bytes to come there. Where no known code follows a byte it skips to the next byte pair that
 * may start a frame (its _POSSIBLE_START, or the buffer's last byte) in one step, which must end by `limit`;
 * elsewhere _match decides. */
static Py_ssize_t noise_span(const Line *L, Py_ssize_t start, Py_ssize_t limit, int *wait) {
    Py_ssize_t i = start, n = L->size;
    *wait = 0;
    while (i < limit) {
        if (n - i < MIN_ADU) {
            *wait = 1;
            break;
        }
        if (known_slot[L->b[i + 1] & 0x7F] >= 0) {
            int taken = nz_take(L, i);
            *wait = taken == NZ_WAIT;
            if (taken != NZ_NOISE) break;
            i++;
            continue;
        }
        int bounded = nz_bounded_run(L, i);
        if (bounded != NZ_NOISE) {
            *wait = bounded == NZ_WAIT;
            break;
        }
        Py_ssize_t next = i + 1;
        while (next + 1 < n && known_slot[L->b[next + 1] & 0x7F] < 0) next++;
        if (next + 1 >= n) next = n - 1;
        if (next > limit) break;
        i = next;
    }
    return i;
}

/* A list of absolute stream offsets as buffer indexes (less `base`), into *out (PyMem): 0, -1 an exception. */
static int nz_offsets(PyObject *list, long long base, Py_ssize_t **out, Py_ssize_t *count) {
    *count = PyList_Size(list);
    if (*count < 0) return -1;
    *out = PyMem_Malloc((size_t)(*count ? *count : 1) * sizeof **out);
    if (*out == NULL) return PyErr_NoMemory(), -1;
    for (Py_ssize_t k = 0; k < *count; k++) {
        long long at = PyLong_AsLongLong(PyList_GET_ITEM(list, k));
        if (at == -1 && PyErr_Occurred()) return -1;
        (*out)[k] = (Py_ssize_t)(at - base);
    }
    return 0;
}

/* noise_span(buffer, limit, expect_slave, expect_function, echo, glitchy, base, ends, starts) -> (the bytes from
 * the buffer's start that the framer would take as noise, its noise run open (see above); whether it waits for
 * bytes to come where they end); ends and starts: the framer's record ends and starts, ascending absolute
 * offsets, `base` the buffer's. */
static PyObject *module_noise_span(PyObject *self, PyObject *args) {
    Py_buffer view, echo;
    Py_ssize_t limit, *ends = NULL, *starts = NULL, end_count = 0, start_count = 0;
    signed char *memo = NULL;
    int slave, function, glitchy;
    long long base;
    PyObject *end_list, *start_list, *result = NULL;
    if (!PyArg_ParseTuple(args, "y*niiy*pLO!O!", &view, &limit, &slave, &function, &echo, &glitchy, &base,
                          &PyList_Type, &end_list, &PyList_Type, &start_list))
        return NULL;
    if (nz_offsets(end_list, base, &ends, &end_count) == 0 && nz_offsets(start_list, base, &starts, &start_count) == 0
        && ((memo = PyMem_Malloc((size_t)end_count + 1)) != NULL || (PyErr_NoMemory(), 0))) {
        memset(memo, -1, (size_t)end_count + 1);
        Line L = {view.buf, view.len, slave, function, echo.buf, echo.len, (char)glitchy, NULL, ends, starts,
                  end_count, start_count, memo};
        int wait;
        Py_ssize_t end = noise_span(&L, 0, limit < view.len ? limit : view.len, &wait);
        result = Py_BuildValue("(nO)", end, wait ? Py_True : Py_False);
    }
    PyMem_Free(memo);
    PyMem_Free(ends);
    PyMem_Free(starts);
    PyBuffer_Release(&view);
    PyBuffer_Release(&echo);
    return result;
}
