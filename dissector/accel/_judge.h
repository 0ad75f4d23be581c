/* The first pass of profile `auto` (app/preselect.py) in the engine: frame and pair, number the frames,
 * and hand over to the Python stages every transaction whose frames the selector must see (a slave it
 * still judges, an identifying function code, FC43, a function the chosen profile does not support:
 * the `judge` bitmap, per slave and function code, made by accel/preselect.py); the others change
 * nothing the selector keeps. No line is written. Included by _summary.c before transaction(). */
#ifndef VW3_JUDGE_H
#define VW3_JUDGE_H

static inline int judged(const Engine *e, const FrameRef *f) {
    int function = f->function & 0x7F;
    return (e->judge[f->slave * 32 + (function >> 3)] >> (function & 7)) & 1;
}

/* One transaction from q (a request to a slave, found at *pos): counted and passed (STEP_DONE), or left. */
static int judge_transaction(Engine *e, const uint8_t *b, Py_ssize_t n, Py_ssize_t *pos, const FrameRef *q) {
    if (judged(e, q)) return STEP_HANDOVER;
    int saved_slave = e->expect_slave, saved_function = e->expect_function;
    e->expect_slave = q->slave;
    e->expect_function = q->function;
    FrameRef a;
    int found = next_frame(e, b, q->at + q->length, n, &a, q->decided);
    if (found == FRAME_OK && a.kind == KIND_REQUEST) { /* unanswered: the next request is its own */
        e->count += 1;
        *pos = a.at;
        e->tl.decided = q->decided;
        return STEP_DONE;
    }
    if (found == FRAME_OK && !judged(e, &a) &&
        !(q->timed && a.timed && e->tl.timeout >= 0 && stamp_seconds(a.ns, q->ns) > e->tl.timeout)) {
        e->count += 2;
        e->expect_slave = e->expect_function = -1;
        *pos = a.at + a.length;
        e->tl.decided = a.decided;
        return STEP_DONE;
    }
    e->expect_slave = saved_slave;
    e->expect_function = saved_function;
    return found == FRAME_NEED ? STEP_NEED : STEP_HANDOVER;
}

#endif
