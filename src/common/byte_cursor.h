/* byte_cursor.h: plain bytes in the machine's order, written and read field by field (the
   saved states of the core and of the FMUs). A read past the end yields zeros and marks
   the reader overrun, so that a short buffer is refused, never over-read. */
#ifndef TRIBO_BYTE_CURSOR_H
#define TRIBO_BYTE_CURSOR_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

typedef struct tribo_writer {
    unsigned char *p;
} tribo_writer;

typedef struct tribo_reader {
    const unsigned char *p, *end;
    int overrun;
} tribo_reader;

static inline void tribo_write_bytes(tribo_writer *w, const void *v, size_t n)
{
    memcpy(w->p, v, n);
    w->p += n;
}
static inline void tribo_write_double(tribo_writer *w, double v) { tribo_write_bytes(w, &v, sizeof v); }
static inline void tribo_write_int(tribo_writer *w, int64_t v) { tribo_write_bytes(w, &v, sizeof v); }

static inline tribo_reader tribo_reader_of(const void *bytes, size_t size)
{
    const tribo_reader r = {bytes, (const unsigned char *)bytes + size, 0};
    return r;
}
static inline void tribo_read_bytes(tribo_reader *r, void *v, size_t n)
{
    if (r->overrun || n > (size_t)(r->end - r->p)) {
        r->overrun = 1;
        memset(v, 0, n);
        return;
    }
    memcpy(v, r->p, n);
    r->p += n;
}
static inline double tribo_read_double(tribo_reader *r)
{
    double v;
    tribo_read_bytes(r, &v, sizeof v);
    return v;
}
static inline int64_t tribo_read_int(tribo_reader *r)
{
    int64_t v;
    tribo_read_bytes(r, &v, sizeof v);
    return v;
}

#endif
