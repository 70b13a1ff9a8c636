/* scenec.c: rt-scenec, the build-time scene compiler: a scene file becomes C data plus the set of effects its tracer needs. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "outpath.h"
#include "scn_parse.h"
#include "topt.h"

static const char *sc_name = "rt-scenec";

static void sc_usage(FILE *f)
{
    fprintf(f,
            "usage: %s SCENE -o OUT.c [--name NAME] [--effects OUT.h]\n"
            "       %s --help | --version\n"
            "  Compiles a scene file into C: OUT.c defines `const scn_desc NAME` (default\n"
            "  scn_compiled); OUT.h defines RT_COMPILED_EFFECTS, the effects the scene can need\n"
            "  over its whole timeline, so that a tracer built with it links no other effect.\n"
            "  -o is short for --output; options take their value as --opt value or\n"
            "  --opt=value, each at most once.\n",
            sc_name, sc_name);
}

/* Writes through a temporary file and a rename: never a half-written output. */
static FILE *sc_open(const char *path, char *tmp, size_t n)
{
    snprintf(tmp, n, "%s.tmp-%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f)
        fprintf(stderr, "%s: %s: cannot write\n", sc_name, path);
    return f;
}

/* Nonzero when paths a and b name the same file: the same name in the same folder (whether or
 * not the file exists yet), or one existing file under two names (a link). */
static int sc_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    const char *ba = strrchr(a, '/'), *bb = strrchr(b, '/');
    if (strcmp(ba ? ba + 1 : a, bb ? bb + 1 : b) != 0)
        return 0;
    char da[4096], db[4096];
    snprintf(da, sizeof da, "%.*s", ba ? (int)(ba - a) + 1 : 1, ba ? a : ".");
    snprintf(db, sizeof db, "%.*s", bb ? (int)(bb - b) + 1 : 1, bb ? b : ".");
    return stat(da, &sa) == 0 && stat(db, &sb) == 0 && sa.st_dev == sb.st_dev &&
        sa.st_ino == sb.st_ino;
}

/* Nonzero for a name the generated C cannot define: a C11 keyword, an identifier reserved to
 * the implementation (_X..., __...) or a macro of the headers it includes. */
static int sc_reserved(const char *name)
{
    static const char *const words[] = {
        "auto",     "break",  "case",   "char",     "const",    "continue", "default",  "do",
        "double",   "else",   "enum",   "extern",   "float",    "for",      "goto",     "if",
        "inline",   "int",    "long",   "register", "restrict", "return",   "short",    "signed",
        "sizeof",   "static", "struct", "switch",   "typedef",  "union",    "unsigned", "void",
        "volatile", "while",  "NULL",   "offsetof", "bool",     "true",     "false"};
    if (name[0] == '_' && ((name[1] >= 'A' && name[1] <= 'Z') || name[1] == '_'))
        return 1;
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (strcmp(name, words[i]) == 0)
            return 1;
    return 0;
}

/* The scene file's name for a comment of the generated C: characters that could end the
 * comment ("*" "/") or form a trigraph ("?"), and control characters, become '_'. */
static const char *sc_comment_path(const char *path)
{
    static char buf[4096];
    size_t i = 0;
    for (; path[i] && i < sizeof buf - 1; i++) {
        char c = path[i];
        buf[i] = c < ' ' || c > '~' || c == '*' || c == '?' || c == '\\' ? '_' : c;
    }
    buf[i] = 0;
    return buf;
}

static const char *const sc_effect_names[] = {"shadow",  "specular", "reflect",
                                              "refract", "texture",  "noise"};

/* The options, in the grammar of render's (topt.h). */
enum { SC_HELP, SC_VERSION, SC_OUTPUT, SC_NAME, SC_EFFECTS, SC_NOPTS };
static const topt sc_opts[SC_NOPTS] = {{"--help", "-h", 0},
                                       {"--version", NULL, 0},
                                       {"--output", "-o", 1},
                                       {"--name", NULL, 1},
                                       {"--effects", NULL, 1}};

int main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *hdr = NULL, *name = "scn_compiled";
    unsigned given = 0;
    for (int i = 1; i < argc; i++) {
        const char *v;
        switch (topt_next(sc_name, sc_opts, SC_NOPTS, argc, argv, &i, &given, &v)) {
        case TOPT_FAIL: return 2;
        case SC_HELP: sc_usage(stdout); return 0;
        case SC_VERSION: topt_version(stdout, sc_name); return 0;
        case SC_OUTPUT: out = v; break;
        case SC_EFFECTS: hdr = v; break;
        case SC_NAME:
            name = v;
            for (const char *c = name; *c; c++)
                if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || *c == '_' ||
                      (c > name && *c >= '0' && *c <= '9')))
                    return topt_error(sc_name, "--name", "expected a C identifier", name);
            if (!*name || sc_reserved(name))
                return topt_error(sc_name, "--name",
                                  "expected a C identifier that is not a keyword or reserved",
                                  name);
            break;
        default:
            if (in) {
                fprintf(stderr, "%s: %s: unexpected argument, a second scene (see %s --help)\n",
                        sc_name, argv[i], sc_name);
                return 2;
            }
            in = argv[i];
        }
    }
    if (!in || !out) {
        fprintf(stderr, "%s: %s (usage: %s SCENE -o OUT.c; see %s --help)\n", sc_name,
                !in ? "no scene file given" : "no output given (-o OUT.c)", sc_name, sc_name);
        return 2;
    }
    /* Each output its own file, neither of them the scene. */
    if (sc_same_file(out, in) || (hdr && sc_same_file(hdr, in))) {
        fprintf(stderr, "%s: %s: the output would replace the scene file %s\n", sc_name,
                sc_same_file(out, in) ? out : hdr, in);
        return 2;
    }
    if (hdr && sc_same_file(out, hdr)) {
        fprintf(stderr, "%s: --effects: %s is the same file as -o %s\n", sc_name, hdr, out);
        return 2;
    }
    static scn_file f;
    char err[512];
    /* Outputs that cannot be created are refused before anything is done. */
    if (outpath_check(out, err, sizeof err) != 0 ||
        (hdr && outpath_check(hdr, err, sizeof err) != 0)) {
        fprintf(stderr, "%s: %s\n", sc_name, err);
        return 2;
    }
    if (scn_load(in, &f, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", sc_name, err);
        return 2;
    }
    /* Both outputs go to temporary files first and are renamed only when both are complete. */
    char tmp_c[4096], tmp_h[4096];
    unsigned fx = scn_effects_union(&f.desc);
    FILE *fo = sc_open(out, tmp_c, sizeof tmp_c);
    if (!fo)
        return 1;
    const char *comment = sc_comment_path(in);
    int ok = scn_write_c(fo, &f.desc, name, comment) == 0, wrote_h = 0;
    ok = fclose(fo) == 0 && ok;
    if (ok && hdr) {
        FILE *fh = sc_open(hdr, tmp_h, sizeof tmp_h);
        if (!fh) {
            remove(tmp_c);
            return 1;
        }
        fprintf(fh,
                "/* Effects of the scene %s over its whole timeline (generated by rt-scenec). */\n",
                comment);
        fprintf(fh, "#define RT_COMPILED_EFFECTS %uu /*", fx);
        for (int b = 0; b < 6; b++)
            if (fx & (1u << b))
                fprintf(fh, " %s", sc_effect_names[b]);
        fprintf(fh, " */\n");
        ok = !ferror(fh);
        ok = fclose(fh) == 0 && ok;
        if (!ok || rename(tmp_h, hdr) != 0) {
            remove(tmp_h);
            remove(tmp_c);
            fprintf(stderr, "%s: %s: cannot write\n", sc_name, hdr);
            return 1;
        }
        wrote_h = 1;
    }
    if (!ok || rename(tmp_c, out) != 0) {
        remove(tmp_c);
        if (wrote_h)
            remove(hdr); /* not one output without the other */
        fprintf(stderr, "%s: %s: cannot write\n", sc_name, out);
        return 1;
    }
    fprintf(stderr, "%s: %s -> %s (%d objects, %d lights, %d tracks; effects:", sc_name, in, out,
            f.desc.nobjects, f.desc.nlights, f.desc.ntracks);
    for (int b = 0; b < 6; b++)
        if (fx & (1u << b))
            fprintf(stderr, " %s", sc_effect_names[b]);
    fprintf(stderr, "%s)\n", fx ? "" : " none");
    return 0;
}
