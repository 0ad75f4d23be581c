/* Framing and pairing alone, for callers that want the frames, not the lines:
 * - the first pass of profile `auto` (app/preselect.py): frame and pair, number the frames, and hand
 *   over to the Python stages every transaction whose frames the selector must see (a slave it still
 *   judges, an identifying function code, FC43, a function the chosen profile does not support: the
 *   `judge` bitmap, per slave and function code, made by accel/preselect.py); the others change
 *   nothing the selector keeps;
 * - with `frames` set (accel/framespath.py: -V, --json, -T, --stats... of a pcap), each transaction
 *   passed is written out as a record (FRAMES_RECORD below) for the Python stages to decode and show.
 * transaction() passes such a transaction at once when its request and answer are not judged. Included by
 * _summary.c before transaction(). */
#ifndef VW3_JUDGE_H
#define VW3_JUDGE_H

/* One transaction: request offset, answer offset (-1: unanswered), lengths, answer kind, whether each
 * has a time, their times and their Tails (struct "=qqiiBBBqqqqii": accel/framespath.py RECORD). */
static int frames_record(Engine *e, const FrameRef *q, const FrameRef *a) {
    if (!e->frames) return 1;
    struct __attribute__((packed)) {
        long long q_at, a_at;
        int32_t q_length, a_length;
        uint8_t a_kind, q_timed, a_timed;
        long long q_ns, a_ns, q_tail_ns, a_tail_ns;
        int32_t q_tail_chars, a_tail_chars;
    } record = {q->at, a ? a->at : -1, (int32_t)q->length, a ? (int32_t)a->length : 0, (uint8_t)(a ? a->kind : 0),
                (uint8_t)q->timed, (uint8_t)(a ? a->timed : 0), q->ns, a ? a->ns : 0, q->tail_ns, a ? a->tail_ns : 0,
                (int32_t)q->tail_chars, a ? (int32_t)a->tail_chars : 0};
    out_put(&e->out, (const char *)&record, sizeof record);
    return e->out.failed ? -1 : 1;
}

/* The judge bitmap's bit of the frame's slave (32 bytes each) and function code. */
static inline int judged(const Engine *e, const FrameRef *f) {
    return bit((const uint8_t *)PyBytes_AS_STRING(e->judge) + f->slave * 32, f->function & 0x7F);
}

#endif
