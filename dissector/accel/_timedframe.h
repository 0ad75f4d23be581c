/* framing/rtu.py's decision on a frame start when the stream comes in chunks (pcap records...): the
 * Python framer first looks at a frame start with the bytes of the chunks fed so far, and takes the
 * frame on its fast path only when the byte after it has come and is not 00; otherwise (a record that
 * ends with the frame, the usual pcap) its careful path (_match) decides, where a record's end is
 * evidence. This mirrors both for the frames it can show and hands everything else over: any other
 * layout that checks out too or may once more bytes come, a CRC scan, a glitch address, a silence
 * inside the frame (a warning). Included by _summary.c after frame_at's helpers. */
#ifndef VW3_TIMEDFRAME_H
#define VW3_TIMEDFRAME_H

/* Interpretation `rule` at i with the bytes up to n, as _match weighs it: 1 it checks out, 0 it does
 * not apply or fails its CRC, 2 it waits for more bytes (its length, or NEED: *waiting_length -1),
 * -1 a CRC scan (hand over). */
static int other_layout(const LengthRule *rule, const uint8_t *b, Py_ssize_t i, Py_ssize_t n,
                        Py_ssize_t *waiting_length) {
    Length length = rule_length(rule, b, i, n);
    if (length.what == LENGTH_SCAN) return -1;
    if (length.what == LENGTH_NEED) {
        *waiting_length = -1;
        return 2;
    }
    if (length.value < MIN_ADU || length.value > MAX_ADU) return 0;
    if (i + length.value > n) {
        *waiting_length = length.value;
        return 2;
    }
    Py_ssize_t stop = i + length.value - 2;
    return crc16(b + i, stop - i) == (uint16_t)(b[stop] | b[stop + 1] << 8);
}

/* rules.quantity_rule, as other_layout answers. */
static int quantity_layout(const QuantityRule *q, const uint8_t *b, Py_ssize_t i, Py_ssize_t n,
                           Py_ssize_t *waiting_length) {
    int need = q->position + 1 > q->count_position ? q->position + 1 : q->count_position;
    if (i + need >= n) {
        *waiting_length = -1;
        return 2;
    }
    Py_ssize_t quantity = (Py_ssize_t)word(b + i + q->position);
    Py_ssize_t length = q->extra + (q->unit ? quantity * q->unit : (quantity + 7) / 8);
    if (length == q->count_extra + b[i + q->count_position] || length < MIN_ADU || length > MAX_ADU) return 0;
    if (i + length > n) {
        *waiting_length = length;
        return 2;
    }
    Py_ssize_t stop = i + length - 2;
    return crc16(b + i, stop - i) == (uint16_t)(b[stop] | b[stop + 1] << 8);
}

/* frame_at for a chunked stream (e->tl.active). */
static int timed_frame_at(Engine *e, const uint8_t *b, Py_ssize_t i, Py_ssize_t n, FrameRef *f, long long decided) {
    Timeline *t = &e->tl;
    long long at = t->base + i;
    if (n - i < MIN_ADU) return FRAME_NEED;
    /* The Python framer's buffer end when it first looks at i: the chunk holding byte i + 3 has come,
     * and the frame before was decided. */
    long long seen = chunk_end(t, chunk_of(t, at + MIN_ADU - 1));
    if (seen < decided) seen = decided;
    Py_ssize_t m = (Py_ssize_t)(seen - t->base);
    if (m > n) return FRAME_NEED;
    int slave = b[i], function = b[i + 1];
    if (slave > MAX_SLAVE || slave == 0) return FRAME_HANDOVER; /* glitch addresses: _match weighs them */
    int kind = frame_kind(e, slave, function);
    if (kind < 0) return kind;
    int scanned;
    Py_ssize_t length = first_length(e, b, i, m, function, kind, &scanned);
    if (scanned || length < 0) return FRAME_HANDOVER; /* a scan, or the rule waits: the careful path's */
    if (i + length > m) return FRAME_HANDOVER;      /* _match would wait for the rest */
    Py_ssize_t stop = i + length - 2;
    if (crc16(b + i, stop - i) != (uint16_t)(b[stop] | b[stop + 1] << 8)) return FRAME_HANDOVER;
    if (!(i + length < m && b[i + length] != 0)) {
        /* _match: this layout checks out; it stands alone unless another one does too, or may. */
        if (kind != KIND_EXCEPTION) {
            int k = known_slot[function];
            const LengthRule *other = kind == KIND_RESPONSE ? &known_request_rule[k] : &known_response_rule[k];
            Py_ssize_t waiting[2] = {0, 0}, valid[2] = {0, 0};
            int found[2] = {other_layout(other, b, i, m, &waiting[0]), 0};
            if (known_quantity_rule[k].position)
                found[1] = quantity_layout(&known_quantity_rule[k], b, i, m, &waiting[1]);
            int others = 0;
            for (int w = 0; w < 2; w++) {
                if (found[w] < 0) return FRAME_HANDOVER;
                if (found[w] == 1) {
                    others = 1;
                    /* (the checked length: other_layout's rule again, or the quantity's) */
                    valid[w] = 1;
                }
            }
            if (others) {
                /* Two layouts check out (a FC23 request whose response reading is as long, FC5's
                 * echo): a record's end after this one picks it, the first tried, unless a shorter
                 * one checks out too (the framer tries the shortest first on a glitchy line). */
                if (!boundary_at(t, at + length)) return FRAME_HANDOVER;
                Py_ssize_t shortest = length;
                if (valid[0]) {
                    Length other_length = rule_length(other, b, i, m);
                    if (other_length.value < shortest) shortest = other_length.value;
                }
                if (valid[1]) {
                    const QuantityRule *q = &known_quantity_rule[k];
                    Py_ssize_t quantity = (Py_ssize_t)word(b + i + q->position);
                    Py_ssize_t other_length = q->extra + (q->unit ? quantity * q->unit : (quantity + 7) / 8);
                    if (other_length < shortest) shortest = other_length;
                }
                if (shortest < length) return FRAME_HANDOVER;
            } else {
                int expected = kind == KIND_RESPONSE; /* the answer awaited */
                for (int w = 0; w < 2; w++)
                    if ((waiting[w] == -1 || waiting[w] == length + 1) && !expected && !boundary_at(t, at + length))
                        return FRAME_HANDOVER; /* the Python framer waits: decided later, maybe otherwise */
            }
        }
    }
    if (silence_inside(t, at, length)) return FRAME_HANDOVER;
    Py_ssize_t k = chunk_of(t, at);
    f->at = i;
    f->length = length;
    f->kind = kind;
    f->slave = slave;
    f->function = function;
    f->timed = (t->flags[k] & CHUNK_TIMED) != 0;
    f->ns = t->ns[k];
    f->decided = seen;
    return FRAME_OK;
}

#endif
