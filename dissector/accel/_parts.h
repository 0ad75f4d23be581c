/* A parameter that codes of two protocol tables count (an ATV71's 8502 read by FC4, its input registers in the
 * protocol, and written by FC6: the ATV71 reads both with one table) keeps the story each table's codes tell
 * apart too, its parts (Stats.parts, keyed param_key(slave, origin, address)): when profile `auto` takes that
 * choice back (standard input, one pass), the parameter parts into them (rehome), as the file, named with the
 * last choice throughout, counts them. stats_store.ParameterTable._part, .rehome, ._join. Included by _stats.h. */

static int tables_valid(const char *tables, Py_ssize_t size, const char *what);

/* p's references taken once more: a copy of p holds them too. */
static Param param_copy(const Param *p) {
    Param copy = *p;
    PyObject *held[] = {copy.text, copy.namer, copy.code, copy.code_namer, copy.status};
    for (size_t k = 0; k < sizeof held / sizeof *held; k++) Py_XINCREF(held[k]);
    return copy;
}

/* The part of (slave, origin, address), made (zeroed, origins set) where none is kept; *created says so. NULL
 * with an exception set: no memory. */
static Param *part_get(Stats *st, int slave, int origin, unsigned address, int *created) {
    uint32_t key = param_key(slave, origin, address);
    Param *part = dense_find(&st->parts, &PARAM_KIND, &key);
    if ((*created = part == NULL) && (part = dense_add(&st->parts, &PARAM_KIND, &key, 0)) != NULL)
        part->origins = (uint8_t)(1u << origin);
    return part;
}

/* The origin (the protocol table) of a part or of a parameter of one origin. */
static int only_origin(const Param *p) {
    int t = 0;
    while (t < PARAM_TABLES - 1 && !(p->origins >> t & 1)) t++;
    return t;
}

/* param_event's event of p (kept by the codes of a table not `origin`'s so far, or of two) told to its
 * `origin`'s part too; at p's second origin, p's story so far becomes its first origin's part. 0, -1: an error. */
static int part_event(Stats *st, Param *p, int slave, int origin, unsigned address, unsigned value, int event,
                      PyObject *code, PyObject *status, PyObject *text, PyObject *namer, int mapped) {
    int created;
    if (!(p->origins & (p->origins - 1))) {
        Param *first = part_get(st, slave, only_origin(p), address, &created);
        if (first == NULL) return -1;
        if (!created) param_release(first); /* (a part left behind: none should be) */
        *first = param_copy(p), first->key = param_key(slave, only_origin(p), address);
    }
    Param *part = part_get(st, slave, origin, address, &created);
    if (part == NULL) return -1;
    return param_apply(part, created, address, value, event, code, status, text, namer, mapped, st->states + 1) < 0
               ? -1 : 0;
}

/* stats_store.join: `moved`'s story joined to `kept`'s (the same parameter kept in two tables, or a part's):
 * counts and changes summed, one change more where the two last states differ, the later state kept; `moved`'s
 * references taken or released. 0, or -1 with an exception set. */
static int param_merge(Param *kept, Param *moved) {
    for (int j = 0; j < PARAM_COUNTS; j++) kept->counts[j] += moved->counts[j];
    kept->origins |= moved->origins;
    Param *first = kept->order <= moved->order ? kept : moved, *later = first == kept ? moved : kept;
    if (first->has_last && later->has_last) {
        int same = same_state(first, later->last, later->status);
        if (same < 0) return -1;
        if (!same) kept->counts[PARAM_CHANGES]++;
    }
    if (later == moved && moved->has_last) {
        Py_XSETREF(kept->status, moved->status);
        Py_XSETREF(kept->text, moved->text);
        Py_XSETREF(kept->namer, moved->namer);
        moved->status = moved->text = moved->namer = NULL; /* (taken) */
        kept->last = moved->last, kept->has_last = 1, kept->last_mapped = moved->last_mapped, kept->order = moved->order;
    }
    if (kept->code == NULL) kept->code = moved->code, moved->code = NULL;
    param_release(moved);
    return 0;
}

/* stats_store.homes_of: the one table homes[t] gives p's origins t, -1 where they are apart there. */
static int param_home(const Param *p, const char *homes, Py_ssize_t size) {
    int found = -1;
    for (Py_ssize_t t = 0; t < size; t++) {
        if (!(p->origins >> t & 1) || found == (uint8_t)homes[t]) continue;
        if (found >= 0) return -1;
        found = (uint8_t)homes[t];
    }
    return found < 0 ? (int)PARAM_TABLE(p->key) : found;
}

/* ParameterTable._join: `moved` (its references taken, then zeroed) kept at `key` of `into`, joined to the
 * parameter kept there, their parts kept where their origins are two now. 0, or -1 with an exception set. */
static int param_place(Stats *st, Dense *into, uint32_t key, Param *moved) {
    Param *kept = dense_find(into, &PARAM_KIND, &key);
    if (kept == NULL) {
        if ((kept = dense_add(into, &PARAM_KIND, &key, 0)) == NULL) return -1;
        *kept = *moved, kept->key = key;
        memset(moved, 0, sizeof *moved); /* (its references are kept's now) */
        return 0;
    }
    uint8_t origins = kept->origins | moved->origins;
    for (int k = 0; (origins & (origins - 1)) && k < 2; k++) {
        Param *one = k ? moved : kept, copy;
        if (one->origins & (one->origins - 1)) continue; /* (two origins: its parts are kept) */
        int created;
        Param *part = part_get(st, (int)PARAM_SLAVE(key), only_origin(one), PARAM_ADDRESS(key), &created);
        if (part == NULL) return -1;
        uint32_t part_key = part->key;
        copy = param_copy(one);
        if (created) *part = copy, part->key = part_key;
        else if (param_merge(part, &copy) < 0) return -1;
    }
    return param_merge(kept, moved);
}

/* rehome(slave, homes): ParameterTable.rehome, the slave's parameters moved to the tables homes (bytes, by table:
 * stats_store.SlaveTables) gives their codes' protocol tables, or parted into their parts where those are apart
 * there: the table built again, in the order first seen. */
static PyObject *stats_rehome(Stats *st, PyObject *args) {
    int slave;
    const char *homes;
    Py_ssize_t size;
    if (!PyArg_ParseTuple(args, "iy#", &slave, &homes, &size)) return NULL;
    if (slave < 0 || slave > 255 || size > PARAM_TABLES)
        return PyErr_Format(PyExc_ValueError, "rehome: slave 0..255, %d tables at most", PARAM_TABLES);
    if (tables_valid(homes, size, "rehome: tables") < 0) return NULL;
    Dense rebuilt = {0};
    for (size_t k = 0; k < st->params.count; k++) {
        Param *p = &PARAMS(st)[k];
        unsigned address = PARAM_ADDRESS(p->key);
        int table = (int)PARAM_SLAVE(p->key) == slave ? param_home(p, homes, size) : (int)PARAM_TABLE(p->key);
        Param pieces[PARAM_TABLES];
        int n = 0, whole = table >= 0;
        for (int t = 0; !whole && t < size; t++) {
            uint32_t key = param_key(slave, t, address);
            const Param *part = p->origins >> t & 1 ? dense_find(&st->parts, &PARAM_KIND, &key) : NULL;
            if (part != NULL) pieces[n++] = *part;
            else whole = p->origins >> t & 1;
        }
        if (whole) { /* (its parts, if any, stay its own) */
            uint32_t key = table >= 0 ? param_key((int)PARAM_SLAVE(p->key), table, address) : p->key;
            if (param_place(st, &rebuilt, key, p) < 0) goto failed;
            continue;
        }
        for (int j = 0; j < n; j++) { /* taken out of the parts first: zeroed in place (key 0, a parameter's never:
                                        * no look-up finds it; it holds no reference) */
            uint32_t key = param_key(slave, only_origin(&pieces[j]), address);
            memset(dense_find(&st->parts, &PARAM_KIND, &key), 0, sizeof(Param));
        }
        for (int j = 0; j < n; j++)
            if (param_place(st, &rebuilt, param_key(slave, (uint8_t)homes[only_origin(&pieces[j])], address),
                            &pieces[j]) < 0)
                goto failed;
        param_release(p);
    }
    dense_free(&st->params);
    st->params = rebuilt;
    Py_RETURN_NONE;
failed: /* no memory (the run ends on it): what was moved is dropped, each reference released once */
    for (size_t k = 0; k < rebuilt.count; k++) param_release(&((Param *)rebuilt.items)[k]);
    dense_free(&rebuilt);
    return NULL;
}
