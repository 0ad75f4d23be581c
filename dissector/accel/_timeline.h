/* The chunks a timed source delivered (pcap and pcapng records, each a framer chunk): where each
 * starts in the byte stream, its time, whether a record ends after it and whether the line was silent
 * for t3.5 before it. The engine needs them to do what the Python stages do with the same chunks
 * (dissector/accel/timedpath.py): the framer decides a frame when the chunk its last byte needs has
 * come, and a record's end or a silence is evidence (framing/rtu.py _match, stream.py feed); a frame's
 * time is its first chunk's (stream.py _time_at); a silence inside a frame is a warning
 * (timing.inner_gaps); a response later than the timeout is no answer (pairing.py); and the time
 * column and response times of the summary line (render/timefmt.py, summary.py).
 *
 * Times are the sources' integer nanoseconds (model.Stamp): two stamps subtract exactly, as there.
 * Included by _summary.c before the Engine type, which holds one Timeline. */
#ifndef VW3_TIMELINE_H
#define VW3_TIMELINE_H

/* The time column's references (timefmt.Clock): first timed item, previous timed item. */
typedef struct {
    int has_first, has_previous;
    long long first_ns, previous_ns;
} ClockRefs;

typedef struct {
    int active;              /* run_timed() is running: chunks below; 0: an untimed raw stream */
    long long base;          /* stream offset of the buffer's first byte */
    const long long *start;  /* chunk starts (stream offsets, ascending); chunk k ends where k+1 starts */
    const long long *ns;     /* chunk times (valid where CHUNK_TIMED) */
    /* CLOCK_PACKETS: per chunk the time of the packet captured before its first byte's (NO_BEFORE: none), the
     * network or several-interface capture's -t d reference (sources/ethernet.py PacketTimes.before); else NULL. */
    const long long *before;
    const uint8_t *flags;
    Py_ssize_t count;
    long long end;           /* stream offset of the end of the last chunk given (the buffer's end) */
    Py_ssize_t cursor;       /* the chunk looked up last (run_timed starts it at 0; count >= 1) */
    long long decided;       /* the Python framer's buffer end when it decided the last frame */
    /* Settings (set_timing): the line's character time and t1.5, the pairing timeout (< 0: none). */
    double char_time, t15, timeout;
    int clock;               /* timedpath.CLOCKS: CLOCK_RELATIVE (-t r), CLOCK_PACKETS, else deltas (-t d, dd) */
    int nanos;               /* the column in ns, 9 decimals (a nanosecond capture), else in us */
    ClockRefs refs;
} Timeline;

#define NO_BEFORE LLONG_MIN /* Timeline.before: the item's packet is the capture's first */

/* Index of the chunk holding stream offset `at` (start[k] <= at < its end). */
static Py_ssize_t chunk_of(Timeline *t, long long at) {
    Py_ssize_t k = t->cursor;
    while (k > 0 && t->start[k] > at) k--;
    while (k + 1 < t->count && t->start[k + 1] <= at) k++;
    t->cursor = k;
    return k;
}

static inline long long chunk_end(const Timeline *t, Py_ssize_t k) {
    return k + 1 < t->count ? t->start[k + 1] : t->end;
}

/* StreamFramer._boundary_at: a record ends, or a silence of t3.5 begins a chunk, at stream offset `at`. */
static int boundary_at(Timeline *t, long long at) {
    if (at <= t->start[0] || at > t->end) return 0;
    Py_ssize_t k = chunk_of(t, at - 1); /* the chunk `at` ends or lies in */
    if (chunk_end(t, k) != at) return 0;
    if (t->flags[k] & CHUNK_RECORD_END) return 1;
    return k + 1 < t->count && (t->flags[k + 1] & CHUNK_SILENCE_BEFORE);
}

/* A stamp's float past 2^53 ns (stamp_seconds' far case; model.Stamp(ns)): ns / 1e9 rounded once, as
 * Python's int / int. */
static double stamp_far(long long ns) {
    if (ns < 0) return -stamp_far(-ns);
    double d = (double)((long double)ns / 1e9L), best = d;
#ifdef __SIZEOF_INT128__
    /* d is within an ulp: pick the nearest of d and its neighbours, exactly (units of 2^-29 s: d >= 2^23). */
    __int128 target = (__int128)ns << 29, best_error = -1;
    double candidates[3] = {nextafter(d, 0.0), d, nextafter(d, INFINITY)};
    for (int k = 0; k < 3; k++) {
        int exponent;
        double fraction = frexp(candidates[k], &exponent);
        long long mantissa = (long long)ldexp(fraction, 53);
        __int128 error = ((__int128)mantissa << (exponent - 24)) * 1000000000 - target;
        if (error < 0) error = -error;
        if (best_error < 0 || error < best_error || (error == best_error && !(mantissa & 1))) {
            best_error = error;
            best = candidates[k];
        }
    }
#endif
    return best;
}

/* Seconds between two stamps, as model.Stamp.__sub__: (ns - ns) / 1e9 rounded once; a stamp's own float
 * (model.Stamp(ns)) with earlier 0. */
static inline double stamp_seconds(long long later, long long earlier) {
    long long ns = later - earlier;
    return ns > -(1LL << 53) && ns < (1LL << 53) ? (double)ns / 1e9 : stamp_far(ns); /* both exact: one rounding */
}

/* timing.line_silence: the line's silence, s, from a chunk (at `from`, time `from_ns`) to the next (`start`,
 * `ns`): their time apart less the first one's bytes' (inside a frame here, t3.5 in scan_pcap). */
static inline double line_silence(long long from, long long from_ns, long long start, long long ns, double char_time) {
    return stamp_seconds(ns, from_ns) - (double)(start - from) * char_time;
}

/* timing.inner_gaps: is there a silence longer than t1.5 before a chunk starting inside the frame at
 * [at, at + length)? (The warning is the Python stages' to write: the frame is handed over.) */
static int silence_inside(Timeline *t, long long at, Py_ssize_t length) {
    Py_ssize_t k = chunk_of(t, at);
    for (; k + 1 < t->count && t->start[k + 1] < at + length; k++) {
        if (!(t->flags[k] & CHUNK_TIMED) || !(t->flags[k + 1] & CHUNK_TIMED)) continue;
        if (line_silence(t->start[k], t->ns[k], t->start[k + 1], t->ns[k + 1], t->char_time) > t->t15) return 1;
    }
    return 0;
}

/* q / 10^digits as fixed-point text with `digits` places (none: no point), minus when `negative`, into
 * text[64]: its length. */
static inline int fixed_digits(char *text, unsigned long long q, int digits, int negative) {
    char digits_out[64], *p = digits_out + sizeof digits_out;
    for (int k = 0; k < digits; k++, q /= 10) *--p = (char)('0' + q % 10);
    if (digits) *--p = '.';
    do *--p = (char)('0' + q % 10); while (q /= 10);
    if (negative) *--p = '-';
    int n = (int)(digits_out + sizeof digits_out - p);
    memcpy(text, p, (size_t)n);
    return n;
}

/* The text of a double as Python's f"{value:.{digits}f}" (both round the exact binary value, half to
 * even) into text[64], its length (0: too long): value = m * 2^e exactly, so value * 10^digits is
 * m * 10^digits shifted, rounded on the bits shifted out; snprintf (a third of a pcap summary's time)
 * only for what that does not hold. */
static int fixed_text(char *text, double value, int digits) {
#ifdef __SIZEOF_INT128__
    int exponent;
    double fraction = frexp(fabs(value), &exponent);
    if (isfinite(value) && digits >= 0 && digits <= 9 && exponent <= 30) {
        unsigned __int128 scaled = (unsigned long long)ldexp(fraction, 53);
        for (int k = 0; k < digits; k++) scaled *= 10;
        int shift = 53 - exponent; /* value * 10^digits = scaled / 2^shift, shift >= 23 */
        unsigned long long q = 0;
        if (shift < 100) {
            unsigned __int128 whole = scaled >> shift, rest = scaled - (whole << shift);
            unsigned __int128 half = (unsigned __int128)1 << (shift - 1);
            q = (unsigned long long)whole;
            if (rest > half || (rest == half && (q & 1))) q++;
        }
        return fixed_digits(text, q, digits, signbit(value));
    }
#endif
    int n = snprintf(text, 64, "%.*f", digits, value);
    return n > 0 && n < 64 ? n : 0;
}

/* f"{value:>{width}.{digits}f}" (a stamp difference: never too long for fixed_text). */
/* text[0..n) right-aligned in `width` columns. */
static void out_padded(Out *o, const char *text, int n, int width) {
    for (int pad = width - n; pad > 0; pad--) out_put(o, " ", 1);
    out_put(o, text, (size_t)n);
}

static void out_fixed(Out *o, double value, int digits, int width) {
    char text[64];
    out_padded(o, text, fixed_text(text, value, digits), width);
}

/* summary_line's head after the number: ` {column:>12} ` (render/timefmt.Clock.text, -t r, d, dd); `before`
 * the time of the packet before the frame's first (CLOCK_PACKETS: its -t d reference; NO_BEFORE: none). */
static void out_time_column(Out *o, Timeline *t, int timed, long long ns, long long before) {
    if (!timed) {
        out_put(o, "            - ", 14);
        return;
    }
    ClockRefs *refs = &t->refs;
    if (!refs->has_first) {
        refs->has_first = 1;
        refs->first_ns = ns;
    }
    /* Its time since its reference: the first timed item (or packet), the packet before its first, else the
     * previous item (none: itself, 0). */
    long long since = t->clock == CLOCK_RELATIVE ? refs->first_ns
                      : t->clock == CLOCK_PACKETS ? (before == NO_BEFORE ? ns : before)
                      : refs->has_previous ? refs->previous_ns : ns;
    refs->has_previous = 1;
    refs->previous_ns = ns;
    out_put(o, " ", 1);
    if (t->nanos) { /* from the integers, as render/timefmt.py Clock._since: a double keeps no 9 decimals */
        long long d = ns - since;
        char text[64];
        out_padded(o, text, fixed_digits(text, (unsigned long long)(d < 0 ? -d : d), 9, d < 0), 12);
    } else {
        out_fixed(o, stamp_seconds(ns, since), 6, 12);
    }
    out_put(o, " ", 1);
}

/* The pairing text of an answer: `[#N]`, or `[#N, 17.8 ms]` when both frames have times. */
static void out_pairing(Out *o, unsigned long long request_number, int timed, long long request_ns,
                        long long answer_ns) {
    out_cstr(o, "[#");
    out_uint(o, request_number, 0);
    if (timed) {
        out_put(o, ", ", 2);
        out_fixed(o, stamp_seconds(answer_ns, request_ns) * 1000, 1, 0);
        out_cstr(o, " ms");
    }
    out_put(o, "]", 1);
}

#endif
