/* framing/rtu.py's decision on a frame start when the stream comes in chunks (pcap records...): the
 * Python framer first looks at a frame start with the bytes of the chunks fed so far, and takes the
 * frame on its fast path only when the byte after it has come and is not 00; otherwise (a record that
 * ends with the frame, the usual pcap) its careful path (_match) decides, where a record's end is
 * evidence. This mirrors both for the frames it can show and hands everything else over: any other
 * layout that checks out too or may once more bytes come, a CRC scan, a glitch address, a silence
 * inside the frame (a warning). Included by _summary.c before next_frame, which calls timed_frame. */
#ifndef VW3_TIMEDFRAME_H
#define VW3_TIMEDFRAME_H

/* The other layouts of a frame at i (_match's interpretations after the first) with the bytes up to m:
 * -1 one is a CRC scan (hand over); else how many check out, with the shortest such length in *shortest,
 * and whether one waits for more bytes (NEED, or `length` + 1: the 00 after a frame; not across a record that is
 * a frame of its own) in *waits. */
static int other_layouts(const Engine *e, int function, int kind, const uint8_t *b, Py_ssize_t i, Py_ssize_t m,
                         Py_ssize_t length, Py_ssize_t *shortest, int *waits) {
    const LengthRule *rules[3];
    int count = layouts(function, kind == KIND_RESPONSE, rules), valid = 0;
    *waits = 0;
    for (int w = 1; w < count; w++) {
        Py_ssize_t other;
        int found = rule_check(rules[w], b, i, m, &other);
        if (found < 0) return -1;
        if (found == 2 && (other == -1 || other == length + 1) && !crosses_framed_record(&e->line, i, other, m))
            *waits = 1;
        if (found != 1) continue;
        valid++;
        if (other < *shortest) *shortest = other;
    }
    return valid;
}

/* What the Python framer does at i with the bytes up to m (its buffer when it looks there): take the
 * frame of the first layout (FRAME_OK: *length, its kind), wait for more bytes (FRAME_NEED, its NEED: it
 * looks again at the next chunk), or anything else (FRAME_HANDOVER). */
static int decide_at(Engine *e, const uint8_t *b, Py_ssize_t i, Py_ssize_t m, int function, int kind,
                     Py_ssize_t *length_out) {
    Timeline *t = &e->tl;
    long long at = t->base + i;
    int scanned;
    Py_ssize_t length = first_length(e, b, i, m, function, kind, &scanned);
    *length_out = length;
    if (scanned) {
        /* FC8's Return Query Data (_match, _scan): both layouts scan alike, so both check out at the
         * length found, and the first stands where a record ends there, as the answer awaited, or where
         * what follows is known; the scan waits as _scan does (what follows a match not come yet). */
        if (length < 0) return (int)length;
        if (!boundary_at(t, at + length) && kind != KIND_RESPONSE && valid_frame_at(&e->line, i + length, m, 0, 1) < 0)
            return FRAME_NEED;
        return FRAME_OK;
    }
    if (length == FRAME_HANDOVER) return FRAME_HANDOVER;
    Py_ssize_t shortest = MAX_COUNTED + 1;
    int waits, valid;
    if (length == FRAME_NEED || i + length > m) {
        /* The first layout waits for its bytes: _match waits too, unless another one checks out, or they would
         * swallow a record that is a frame of its own (then _match weighs the others without it). */
        if (crosses_framed_record(&e->line, i, length, m)) return FRAME_HANDOVER;
        if (kind == KIND_EXCEPTION) return FRAME_NEED;
        valid = other_layouts(e, function, kind, b, i, m, length, &shortest, &waits);
        return valid == 0 ? FRAME_NEED : FRAME_HANDOVER;
    }
    if (!crc_ok(b, i, length)) return FRAME_HANDOVER;
    if ((i + length < m && b[i + length] != 0) || kind == KIND_EXCEPTION) return FRAME_OK; /* (its fast path) */
    /* _match: this layout checks out; it stands alone unless another one does too, or may. */
    valid = other_layouts(e, function, kind, b, i, m, length, &shortest, &waits);
    if (valid < 0) return FRAME_HANDOVER;
    if (valid) {
        /* Two layouts check out (a FC23 request whose response reading is as long, FC5's echo): a
         * record's end after this one picks it, the first tried, unless a shorter one checks out too
         * (the framer tries the shortest first on a glitchy line). */
        if (boundary_at(t, at + length) && shortest >= length) return FRAME_OK;
        /* Nothing after it yet (a live read, a record, that ends with the frame; so the others are as
         * long): off a glitchy line, _match takes the answer awaited at once, and waits for what follows
         * anything else (_valid_frame_at there: NEED). */
        if (i + length >= m && shortest >= length && !e->line.glitchy)
            return kind == KIND_RESPONSE ? FRAME_OK : FRAME_NEED;
        return FRAME_HANDOVER;
    }
    if (waits && kind != KIND_RESPONSE && !boundary_at(t, at + length))
        return FRAME_NEED; /* a longer layout may still come (the 00 case) */
    return FRAME_OK;
}

/* The frame f starts (its kind, slave and function found) on a chunked stream (e->tl.active): its length
 * and its time as next_frame gives them. */
static int timed_frame(Engine *e, const uint8_t *b, Py_ssize_t n, FrameRef *f, long long decided) {
    Timeline *t = &e->tl;
    Py_ssize_t i = f->at;
    long long at = t->base + i;
    /* The Python framer's buffer end when it first looks at i: the chunk holding byte i + 3 has come,
     * and the frame before was decided; where it waits, it looks again with the next chunk. */
    long long seen = chunk_end(t, chunk_of(t, at + MIN_ADU - 1));
    if (seen < decided) seen = decided;
    for (;;) {
        if (seen > t->end) return FRAME_NEED;
        int decision = decide_at(e, b, i, (Py_ssize_t)(seen - t->base), f->function, f->kind, &f->length);
        if (decision == FRAME_OK) break;
        if (decision == FRAME_HANDOVER) return FRAME_HANDOVER;
        if (seen >= t->end) return FRAME_NEED;
        seen = chunk_end(t, chunk_of(t, seen));
    }
    if (silence_inside(t, at, f->length)) return FRAME_HANDOVER;
    Py_ssize_t last = chunk_of(t, at + f->length - 1), k = chunk_of(t, at);
    f->timed = (t->flags[k] & CHUNK_TIMED) != 0;
    f->ns = f->tail_ns = t->ns[k];
    f->tail_chars = f->length;
    if (f->timed && (t->flags[last] & CHUNK_TIMED)) { /* (its Tail: stream.py _tail_at) */
        f->tail_ns = t->ns[last];
        f->tail_chars = (Py_ssize_t)(at + f->length - t->start[last]);
    }
    f->before = t->before != NULL ? t->before[k] : NO_BEFORE;
    f->decided = seen;
    return FRAME_OK;
}

#endif
