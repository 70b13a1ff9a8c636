/* scn_lex.c: the scene parser's tokens, number and time syntax, and its error messages. */
#include "scn_lex.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "knobs.h"

int ps_fail_at(ps_state *ps, int line, int col, const char *fmt, ...)
{
    int n = snprintf(ps->err, ps->errlen, "%s:%d:%d: ", ps->path, line, col);
    if (n < 0 || (size_t)n >= ps->errlen)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(ps->err + n, ps->errlen - (size_t)n, fmt, ap);
    va_end(ap);
    return -1;
}

/* The next whitespace-separated token of the line; 0 when the line has no more. */
int ps_next(ps_state *ps, ps_tok *t)
{
    while (ps->p < ps->le && (*ps->p == ' ' || *ps->p == '\t'))
        ps->p++;
    if (ps->p >= ps->le)
        return 0;
    t->s = ps->p;
    while (ps->p < ps->le && *ps->p != ' ' && *ps->p != '\t')
        ps->p++;
    t->len = (int)(ps->p - t->s);
    return 1;
}

void scn_format_q16(int32_t v, char *buf)
{
    int64_t a = v < 0 ? -(int64_t)v : v;
    int64_t whole = a / SCN_ONE;
    /* six decimals, rounded, then trailing zeros dropped */
    int64_t frac = ((a % SCN_ONE) * 1000000 + SCN_ONE / 2) / SCN_ONE;
    if (frac >= 1000000) {
        whole++;
        frac -= 1000000;
    }
    int n = sprintf(buf, "%s%lld", v < 0 ? "-" : "", (long long)whole);
    if (frac) {
        n += sprintf(buf + n, ".%06lld", (long long)frac);
        while (buf[n - 1] == '0')
            buf[--n] = 0;
    }
}

/* The numbers of scene files have the syntax of the command line's (knobs_scan: an optional
 * '-', digits, optionally '.' and digits), and the same range rules. */

/* A decimal number as Q16.16, rounded to nearest; magnitudes of 32768 and more saturate
 * (and then fail every range check). */
int ps_number(ps_state *ps, ps_tok t, const char *what, int32_t *out)
{
    knobs_num n;
    if (knobs_scan(t.s, t.len, &n) != 0)
        return PS_FAIL(ps, t.s, "%s: '%.*s' is not a number", what, t.len, t.s);
    int64_t q = (int64_t)n.whole * SCN_ONE +
        ((int64_t)n.frac * 2 * SCN_ONE + n.frac_pow10) / (2 * (int64_t)n.frac_pow10);
    if (q > INT32_MAX)
        q = INT32_MAX;
    *out = (int32_t)(n.neg ? -q : q);
    return 0;
}

/* A whole number in [lo, hi]: "-3" and "5000" are both numbers out of range, "1.5" and "x" are
 * not whole numbers. */
int ps_int(ps_state *ps, ps_tok t, const char *what, long lo, long hi, int32_t *out)
{
    long v;
    int r = knobs_number(t.s, t.len, 0, lo, hi, &v);
    if (r == KNOBS_NUM_RANGE)
        return PS_FAIL(ps, t.s, "%s: %.*s is out of range (%ld .. %ld)", what, t.len, t.s, lo, hi);
    if (r != KNOBS_NUM_OK)
        return PS_FAIL(ps, t.s, "%s: '%.*s' is not a whole number", what, t.len, t.s);
    *out = (int32_t)v;
    return 0;
}

/* Seconds with at most three decimals, in 0 .. SCN_MAX_DURATION_MS, as milliseconds. */
int ps_time(ps_state *ps, ps_tok t, const char *what, int32_t *ms)
{
    long v;
    int r = knobs_number(t.s, t.len, 3, 0, SCN_MAX_DURATION_MS, &v);
    if (r == KNOBS_NUM_SYNTAX)
        return PS_FAIL(ps, t.s, "%s: '%.*s' is not a time in seconds", what, t.len, t.s);
    if (r == KNOBS_NUM_DECIMALS)
        return PS_FAIL(ps, t.s,
                       "%s: '%.*s' has more than 3 decimals (times are in whole milliseconds)",
                       what, t.len, t.s);
    if (r == KNOBS_NUM_RANGE)
        return PS_FAIL(ps, t.s, "%s: %.*s s is out of range (0 .. %d s)", what, t.len, t.s,
                       SCN_MAX_DURATION_MS / 1000);
    *ms = (int32_t)v;
    return 0;
}

/* The `arity` numbers of parameter `param` after the property token `prop`, range-checked. */
int ps_values(ps_state *ps, ps_tok prop, int param, int32_t out[3])
{
    const scn_param_info *pi = &scn_params[param];
    for (int c = 0; c < pi->arity; c++) {
        ps_tok t;
        if (!ps_next(ps, &t))
            return PS_FAIL(ps, prop.s, "'%.*s' needs %d number%s, found %d", prop.len, prop.s,
                           pi->arity, pi->arity > 1 ? "s" : "", c);
        if (ps_number(ps, t, pi->name, &out[c]) != 0)
            return -1;
        if (out[c] < pi->lo || out[c] > pi->hi) {
            char lo[16], hi[16];
            scn_format_q16(pi->lo, lo);
            scn_format_q16(pi->hi, hi);
            return PS_FAIL(ps, t.s, "%s: %.*s is out of range (%s .. %s)", pi->name, t.len, t.s, lo,
                           hi);
        }
    }
    if ((param == SCN_P_UP || param == SCN_P_NORMAL) && !out[0] && !out[1] && !out[2])
        return PS_FAIL(ps, prop.s, "'%s' must not be the zero vector", pi->name);
    return 0;
}

/* After the last property of a statement: nothing may follow. */
int ps_end(ps_state *ps)
{
    ps_tok t;
    if (ps_next(ps, &t))
        return PS_FAIL(ps, t.s, "unexpected '%.*s' at the end of the line", t.len, t.s);
    return 0;
}

/* A property name that is not one of `expected`: say what went wrong. */
int ps_bad_property(ps_state *ps, ps_tok t, const char *stmt, ps_tok prev, int prev_arity,
                    const char *expected)
{
    if ((t.s[0] >= '0' && t.s[0] <= '9') || t.s[0] == '-' || t.s[0] == '.') {
        if (prev.len)
            return PS_FAIL(ps, t.s, "extra value '%.*s' after '%.*s' (it takes %d)", t.len, t.s,
                           prev.len, prev.s, prev_arity);
        return PS_FAIL(ps, t.s, "unexpected value '%.*s' (expected a property: %s)", t.len, t.s,
                       expected);
    }
    return PS_FAIL(ps, t.s, "unknown property '%.*s' of %s (expected: %s)", t.len, t.s, stmt,
                   expected);
}

/* Marks property bit `bit` as given; a second time is an error. */
int ps_once(ps_state *ps, ps_tok t, unsigned *seen, unsigned bit)
{
    if (*seen & bit)
        return PS_FAIL(ps, t.s, "'%.*s' is given twice", t.len, t.s);
    *seen |= bit;
    return 0;
}

/* The index of t among words[0 .. n-1], or -1. */
int ps_word(ps_tok t, const char *const *words, int n)
{
    for (int i = 0; i < n; i++)
        if (ps_is(t, words[i]))
            return i;
    return -1;
}

/* words[0 .. n-1] as "a, b, c" (last_sep ", ") or "a, b or c" (last_sep " or ") into buf. */
void ps_join(char *buf, size_t size, const char *const *words, int n, const char *last_sep)
{
    size_t len = 0;
    buf[0] = 0;
    for (int i = 0; i < n && len < size; i++) {
        const char *sep = i == 0 ? "" : i < n - 1 ? ", " : last_sep;
        len += (size_t)snprintf(buf + len, size - len, "%s%s", sep, words[i]);
    }
}
