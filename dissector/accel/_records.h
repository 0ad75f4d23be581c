/* Classic pcap records in bulk (sources/pcap.py read_pcap, for the compiled timed path): the records of
 * a buffer become one block (accel/records.py Block): their bytes end to end, and per record its stream
 * offset, its time in ns (Stamp.from_parts: seconds * 1e9 + fraction * 1e9 // units) and its flags
 * (_timeline.h: timed, a record end, a silence of t3.5 before it: timing.silence_before). It stops before
 * a record the Python reader must see (one captured in part, or longer than a chunk: their warnings and
 * splits are its; one whose fraction of a second is 1 s or more: its refusal), and at the buffer's end. Included by _summary.c. */
#ifndef VW3_RECORDS_H
#define VW3_RECORDS_H

enum { SCAN_MORE = 0, SCAN_SPECIAL = 1 };

static uint32_t read_u32(const uint8_t *p, int swapped) {
    uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    if (swapped) v = (v >> 24) | ((v >> 8) & 0xFF00) | ((v << 8) & 0xFF0000) | (v << 24);
    return v;
}

/* scan_pcap(buffer, position, big_endian, units, offset, previous, char_time, t35, chunk_size) ->
 * (data, starts, times, flags, position, stop, records, offset, previous, span); previous: (offset, ns,
 * timed) of the chunk before, or None; span: (lowest, highest) ns of the timed records, or None. */
static PyObject *module_scan_pcap(PyObject *self, PyObject *args) {
    Py_buffer view;
    Py_ssize_t pos, chunk_size;
    int swapped;
    long long units, offset;
    PyObject *previous;
    double char_time, t35;
    if (!PyArg_ParseTuple(args, "y*npLLOddn", &view, &pos, &swapped, &units, &offset, &previous, &char_time, &t35,
                          &chunk_size))
        return NULL;
    long long previous_offset = 0, previous_ns = 0;
    int previous_timed = 0;
    if (previous != Py_None && !PyArg_ParseTuple(previous, "LLp", &previous_offset, &previous_ns, &previous_timed)) {
        PyBuffer_Release(&view);
        return NULL;
    }
    const uint8_t *b = view.buf;
    Py_ssize_t n = view.len, count = 0, size = 0;
    long long records = 0, lowest = 0, highest = 0;
    int stop = SCAN_MORE, timed_seen = 0;
    PyObject *result = NULL;
    /* Per record its stream offset and time and its flag byte, and the records' bytes end to end, in one block: a
     * record takes 16 bytes of header at least, so the buffer holds n / 16 of them at most. */
    size_t most = (size_t)(n > 0 ? n : 0) / 16 + 1;
    long long *starts = PyMem_Malloc(most * (2 * sizeof(long long) + 1 + 16));
    if (starts == NULL || pos < 0 || units <= 0) {
        PyErr_SetString(starts == NULL ? PyExc_MemoryError : PyExc_ValueError,
                        "scan_pcap: bad position or units, or no memory");
        goto done;
    }
    long long *times = starts + most;
    uint8_t *flags = (uint8_t *)(times + most);
    char *data = (char *)(flags + most);
    while (pos + 16 <= n) {
        uint32_t seconds = read_u32(b + pos, swapped), fraction = read_u32(b + pos + 4, swapped);
        uint32_t captured = read_u32(b + pos + 8, swapped), original = read_u32(b + pos + 12, swapped);
        if (captured < original || (Py_ssize_t)captured > chunk_size || fraction >= units) {
            stop = SCAN_SPECIAL;
            break;
        }
        if (pos + 16 + (Py_ssize_t)captured > n) break;
        pos += 16;
        records++;
        if (!captured) continue;
        int timed = seconds || fraction;
        long long ns = timed ? (long long)seconds * 1000000000LL + (long long)fraction * 1000000000LL / units : 0;
        uint8_t flag = CHUNK_RECORD_END | (timed ? CHUNK_TIMED : 0);
        if (timed && previous_timed && line_silence(previous_offset, previous_ns, offset, ns, char_time) >= t35)
            flag |= CHUNK_SILENCE_BEFORE;
        if (timed) {
            if (!timed_seen || ns < lowest) lowest = ns;
            if (!timed_seen || ns > highest) highest = ns;
            timed_seen = 1;
        }
        starts[count] = offset;
        times[count] = ns;
        flags[count] = flag;
        count++;
        memcpy(data + size, b + pos, captured);
        size += captured;
        previous_offset = offset;
        previous_ns = ns;
        previous_timed = timed;
        offset += captured;
        pos += captured;
    }
    PyObject *last = count || previous != Py_None /* the last chunk read here, else the one given */
                         ? Py_BuildValue("(LLi)", previous_offset, previous_ns, previous_timed) : Py_NewRef(Py_None);
    PyObject *span = last == NULL ? NULL : timed_seen ? Py_BuildValue("(LL)", lowest, highest) : Py_NewRef(Py_None);
    /* (Py_BuildValue releases its N arguments when one of them is NULL) */
    result = Py_BuildValue("(y#y#y#y#niLLNN)", data, size, (const char *)starts, count * (Py_ssize_t)sizeof(long long),
                           (const char *)times, count * (Py_ssize_t)sizeof(long long), (const char *)flags, count,
                           pos, stop, records, offset, last, span);
done:
    PyMem_Free(starts);
    PyBuffer_Release(&view);
    return result;
}

#endif
