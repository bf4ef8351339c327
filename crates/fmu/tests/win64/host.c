/* A plain FMI 2.0 co-simulation importer in C, the way a Windows tool loads an FMU: it reads
 * modelDescription.xml of an unpacked FMU, loads binaries/win64/<id>.dll with LoadLibrary
 * (binaries/linux64/<id>.so with dlopen when built natively), and drives it through the fmi2*
 * functions found with GetProcAddress/dlsym. Used by scripts/test-win64.sh: the same source is
 * built with x86_64-w64-mingw32-gcc (run under Wine) and with gcc (run natively on the linux64
 * binary), so both binaries see exactly the same call sequence.
 *
 *   host FMU_DIR OUT.csv          run the sequence below, write the output history
 *   host --compare A.csv B.csv [SPREAD.csv]   compare two histories (see compare());
 *                                 native build only
 *
 * FMU_DIR is the unpacked FMU (a Windows path such as C:\hybeam\case1 under Wine); the resource
 * location passed to fmi2Instantiate is its file URI, file:///C:/hybeam/case1/resources.
 *
 * The sequence: instantiate, setup (no stop time), enter/exit initialization, 50 steps of
 * 0.01 s (0.5 s) with a tip force schedule on every input named tip.force.*, fmi2GetReal of every
 * output after each step. At t = 0.25 s the FMU state is taken, serialized and deserialized;
 * after 0.5 s the deserialized state is set and the last 25 steps are run again (they must
 * repeat bit for bit). Then a NaN input must be refused (fmi2Error), a communication step
 * of 100 s (beyond the work cap) must be an fmi2Discard with fmi2Terminated = false and
 * fmi2LastSuccessfulTime = 0.5, and restoring the state taken before it must let a 0.01 s
 * step succeed. Finally terminate and free the instance; the process must have as many threads
 * as before loading the library. Then unload the library and wait 300 ms, so that a thread
 * left behind would crash visibly.
 * Prints "HOST: OK" and exits 0 when every check held. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#include <tlhelp32.h>
typedef HMODULE lib_t;
#define PLATFORM "win64"
#define SUFFIX ".dll"
static lib_t lib_open(const char *p) { return LoadLibraryA(p); }
static void *lib_sym(lib_t h, const char *n) { return (void *)GetProcAddress(h, n); }
static int lib_close(lib_t h) { return FreeLibrary(h) ? 0 : -1; }
static unsigned long lib_error(void) { return GetLastError(); }
static void pause_ms(int ms) { Sleep(ms); }
/* threads of this process */
static int thread_count(void) {
    HANDLE snap = CreateToolhelp32Snapshot(TH32CS_SNAPTHREAD, 0);
    THREADENTRY32 te;
    int n = 0;
    if (snap == INVALID_HANDLE_VALUE) return -1;
    te.dwSize = sizeof te;
    if (Thread32First(snap, &te)) do {
            if (te.th32OwnerProcessID == GetCurrentProcessId()) n++;
        } while (Thread32Next(snap, &te));
    CloseHandle(snap);
    return n;
}
#define SEP '\\'
#else
#include <dirent.h>
#include <dlfcn.h>
#include <time.h>
typedef void *lib_t;
#define PLATFORM "linux64"
#define SUFFIX ".so"
static lib_t lib_open(const char *p) { return dlopen(p, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(lib_t h, const char *n) { return dlsym(h, n); }
static int lib_close(lib_t h) { return dlclose(h); }
static unsigned long lib_error(void) { return 0; }
static void pause_ms(int ms) {
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}
/* threads of this process */
static int thread_count(void) {
    DIR *d = opendir("/proc/self/task");
    struct dirent *e;
    int n = 0;
    if (!d) return -1;
    while ((e = readdir(d)))
        if (e->d_name[0] != '.') n++;
    closedir(d);
    return n;
}
#define SEP '/'
#endif

/* FMI 2.0 types (fmi2TypesPlatform.h, fmi2FunctionTypes.h) */
typedef void *fmi2Component;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Boolean;
typedef char fmi2Byte;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;
typedef void (*fmi2CallbackLogger)(void *, const char *, fmi2Status, const char *, const char *, ...);
typedef struct {
    fmi2CallbackLogger logger;
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;

typedef const char *(*GetStr)(void);
typedef fmi2Component (*Instantiate)(const char *, fmi2Type, const char *, const char *,
                                     const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef void (*FreeInstance)(fmi2Component);
typedef fmi2Status (*Setup)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*Plain)(fmi2Component);
typedef fmi2Status (*RealIO)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*RealSet)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
typedef fmi2Status (*StateGet)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*StateSet)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*StateSize)(fmi2Component, fmi2FMUstate, size_t *);
typedef fmi2Status (*StateSer)(fmi2Component, fmi2FMUstate, fmi2Byte *, size_t);
typedef fmi2Status (*StateDeser)(fmi2Component, const fmi2Byte *, size_t, fmi2FMUstate *);
typedef fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef fmi2Status (*StatusGet)(fmi2Component, fmi2StatusKind, fmi2Status *);
typedef fmi2Status (*RealStatusGet)(fmi2Component, fmi2StatusKind, fmi2Real *);
typedef fmi2Status (*BoolStatusGet)(fmi2Component, fmi2StatusKind, fmi2Boolean *);

#define MAXV 256
#define STEPS 50
#define H 0.01
#define SNAP 25 /* steps before the state is taken */

static int failures = 0;
#define CHECK(cond, ...)                                  \
    do {                                                  \
        if (!(cond)) {                                    \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);   \
            printf(__VA_ARGS__);                          \
            printf("\n");                                 \
            failures++;                                   \
        }                                                 \
    } while (0)

static int logged_discard = 0;
static void logger(void *env, const char *name, fmi2Status status, const char *category,
                   const char *message, ...) {
    char text[4096];
    va_list ap;
    (void)env;
    va_start(ap, message);
    vsnprintf(text, sizeof text, message, ap);
    va_end(ap);
    if (status == fmi2Discard) logged_discard++;
    printf("  [%s %d %s] %s\n", name ? name : "?", (int)status, category ? category : "?", text);
}

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    long n;
    char *buf;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)n + 1);
    if (fread(buf, 1, (size_t)n, f) != (size_t)n) n = 0;
    buf[n] = 0;
    fclose(f);
    return buf;
}

/* Value of attribute `attr` inside the element starting at `elem` (up to its '>'). */
static int attribute(const char *elem, const char *attr, char *out, size_t cap) {
    const char *end = strchr(elem, '>');
    char key[64];
    const char *p;
    size_t n;
    snprintf(key, sizeof key, " %s=\"", attr);
    p = strstr(elem, key);
    if (!p || (end && p > end)) return 0;
    p += strlen(key);
    n = strcspn(p, "\"");
    if (n >= cap) return 0;
    memcpy(out, p, n);
    out[n] = 0;
    return 1;
}

typedef struct {
    char name[128];
    fmi2ValueReference vr;
} Var;

/* The modelDescription fields this host needs. */
typedef struct {
    char guid[128], id[128];
    Var out[MAXV], in[MAXV];
    int n_out, n_in;
} Model;

static int parse_model(const char *xml, Model *m) {
    const char *p = strstr(xml, "<fmiModelDescription");
    const char *cs = strstr(xml, "<CoSimulation");
    char causality[32], vr[32];
    memset(m, 0, sizeof *m);
    if (!p || !cs || !attribute(p, "guid", m->guid, sizeof m->guid) ||
        !attribute(cs, "modelIdentifier", m->id, sizeof m->id))
        return 0;
    for (p = strstr(xml, "<ScalarVariable"); p; p = strstr(p + 1, "<ScalarVariable")) {
        Var v;
        if (!attribute(p, "name", v.name, sizeof v.name) ||
            !attribute(p, "valueReference", vr, sizeof vr))
            return 0;
        v.vr = (fmi2ValueReference)strtoul(vr, NULL, 10);
        if (!attribute(p, "causality", causality, sizeof causality)) continue;
        if (!strcmp(causality, "output") && m->n_out < MAXV) m->out[m->n_out++] = v;
        if (!strcmp(causality, "input") && !strncmp(v.name, "tip.force.", 10) && m->n_in < MAXV)
            m->in[m->n_in++] = v;
    }
    return m->n_out > 0;
}

/* file URI of DIR/resources: C:\a b\x -> file:///C:/a%20b/x/resources, /a/x -> file:///a/x/resources */
static void resource_uri(const char *dir, char *out, size_t cap) {
    size_t n = 0;
    const char *p = dir;
    n += (size_t)snprintf(out, cap, "file://%s", dir[0] == '/' ? "" : "/");
    for (; *p && n + 4 < cap; p++) {
        if (*p == '\\')
            out[n++] = '/';
        else if (*p == ' ')
            n += (size_t)snprintf(out + n, cap - n, "%%20");
        else
            out[n++] = *p;
    }
    out[n] = 0;
    strncat(out, "/resources", cap - n - 1);
}

/* The tip force schedule (N) of input i before step k: small, within the rod's linear range. */
static double force(int i, int k) {
    if (i == 0) return (k % 40) < 20 ? 0.03 : -0.02;
    return 0.005 * sin(0.1 * k * i);
}

#define LOAD(type, var, name)                                  \
    type var = (type)lib_sym(lib, name);                       \
    if (!var) {                                                \
        printf("FAIL: %s not exported\n", name);               \
        return 2;                                              \
    }

static int run(const char *dir, const char *csv) {
    char path[4096], uri[8192];
    Model m;
    char *xml;
    lib_t lib;
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2Component c;
    fmi2FMUstate snap = NULL, copy = NULL, before = NULL;
    static double hist[STEPS][MAXV], again[STEPS][MAXV];
    double nan_in[MAXV];
    fmi2ValueReference in_vr[MAXV], out_vr[MAXV];
    size_t size = 0;
    fmi2Byte *bytes;
    fmi2Status st;
    fmi2Boolean terminated = -1;
    double last = -1;
    int i, k, threads_before = thread_count(), threads_after;
    FILE *f;

    snprintf(path, sizeof path, "%s%cmodelDescription.xml", dir, SEP);
    xml = read_file(path);
    if (!xml || !parse_model(xml, &m)) {
        printf("FAIL: cannot read %s\n", path);
        return 2;
    }
    free(xml);
    for (i = 0; i < m.n_in; i++) in_vr[i] = m.in[i].vr;
    for (i = 0; i < m.n_out; i++) out_vr[i] = m.out[i].vr;
    snprintf(path, sizeof path, "%s%cbinaries%c" PLATFORM "%c%s" SUFFIX, dir, SEP, SEP, SEP, m.id);
    lib = lib_open(path);
    if (!lib) {
        printf("FAIL: cannot load %s (error %lu)\n", path, lib_error());
        return 2;
    }
    printf("loaded %s: %d inputs tip.force.*, %d outputs\n", path, m.n_in, m.n_out);
    {
        LOAD(GetStr, types_platform, "fmi2GetTypesPlatform");
        LOAD(GetStr, version, "fmi2GetVersion");
        LOAD(Instantiate, instantiate, "fmi2Instantiate");
        LOAD(FreeInstance, free_instance, "fmi2FreeInstance");
        LOAD(Setup, setup, "fmi2SetupExperiment");
        LOAD(Plain, enter_init, "fmi2EnterInitializationMode");
        LOAD(Plain, exit_init, "fmi2ExitInitializationMode");
        LOAD(Plain, terminate, "fmi2Terminate");
        LOAD(RealIO, get_real, "fmi2GetReal");
        LOAD(RealSet, set_real, "fmi2SetReal");
        LOAD(StateGet, get_state, "fmi2GetFMUstate");
        LOAD(StateSet, set_state, "fmi2SetFMUstate");
        LOAD(StateGet, free_state_raw, "fmi2FreeFMUstate");
        LOAD(StateSize, state_size, "fmi2SerializedFMUstateSize");
        LOAD(StateSer, serialize, "fmi2SerializeFMUstate");
        LOAD(StateDeser, deserialize, "fmi2DeSerializeFMUstate");
        LOAD(DoStep, do_step, "fmi2DoStep");
        LOAD(StatusGet, get_status, "fmi2GetStatus");
        LOAD(RealStatusGet, get_real_status, "fmi2GetRealStatus");
        LOAD(BoolStatusGet, get_bool_status, "fmi2GetBooleanStatus");

        CHECK(!strcmp(types_platform(), "default"), "fmi2GetTypesPlatform = %s", types_platform());
        CHECK(!strcmp(version(), "2.0"), "fmi2GetVersion = %s", version());
        resource_uri(dir, uri, sizeof uri);
        printf("resource location %s\n", uri);
        c = instantiate("host", fmi2CoSimulation, m.guid, uri, &cb, 0, 0);
        if (!c) {
            printf("FAIL: fmi2Instantiate returned NULL\n");
            return 2;
        }
        CHECK(setup(c, 0, 0.0, 0.0, 0, 0.0) == fmi2OK, "fmi2SetupExperiment");
        CHECK(enter_init(c) == fmi2OK, "fmi2EnterInitializationMode");
        CHECK(exit_init(c) == fmi2OK, "fmi2ExitInitializationMode");
        for (k = 0; k < STEPS; k++) {
            double u[MAXV];
            if (k == SNAP) {
                CHECK(get_state(c, &snap) == fmi2OK && snap, "fmi2GetFMUstate");
                CHECK(state_size(c, snap, &size) == fmi2OK && size > 0, "size");
                bytes = malloc(size);
                CHECK(serialize(c, snap, bytes, size) == fmi2OK, "fmi2SerializeFMUstate");
                CHECK(deserialize(c, bytes, size, &copy) == fmi2OK && copy, "fmi2DeSerializeFMUstate");
                free(bytes);
                CHECK(free_state_raw(c, &snap) == fmi2OK && !snap, "fmi2FreeFMUstate");
            }
            for (i = 0; i < m.n_in; i++) u[i] = force(i, k);
            CHECK(set_real(c, in_vr, (size_t)m.n_in, u) == fmi2OK, "fmi2SetReal at step %d", k);
            st = do_step(c, k * H, H, 1);
            CHECK(st == fmi2OK, "fmi2DoStep(%g) = %d", k * H, (int)st);
            CHECK(get_real(c, out_vr, (size_t)m.n_out, hist[k]) == fmi2OK, "fmi2GetReal");
        }
        /* the deserialized state at 0.25 s repeats the second half bit for bit */
        CHECK(set_state(c, copy) == fmi2OK, "fmi2SetFMUstate");
        for (k = SNAP; k < STEPS; k++) {
            double u[MAXV];
            for (i = 0; i < m.n_in; i++) u[i] = force(i, k);
            CHECK(set_real(c, in_vr, (size_t)m.n_in, u) == fmi2OK, "fmi2SetReal");
            CHECK(do_step(c, k * H, H, 1) == fmi2OK, "fmi2DoStep after restore");
            CHECK(get_real(c, out_vr, (size_t)m.n_out, again[k]) == fmi2OK, "fmi2GetReal");
            CHECK(!memcmp(again[k], hist[k], sizeof(double) * (size_t)m.n_out),
                  "restored run differs at step %d", k);
        }
        printf("restored state at t = %g: %d steps repeat bit for bit\n", SNAP * H, STEPS - SNAP);
        /* a NaN input is refused (fmi2Error) and changes nothing */
        for (i = 0; i < m.n_in; i++) nan_in[i] = NAN;
        if (m.n_in > 0)
            CHECK(set_real(c, in_vr, (size_t)m.n_in, nan_in) == fmi2Error, "NaN input accepted");
        /* a step over the work cap is an fmi2Discard; the state before it continues */
        CHECK(get_state(c, &before) == fmi2OK, "fmi2GetFMUstate before the discard");
        st = do_step(c, STEPS * H, 100.0, 1);
        CHECK(st == fmi2Discard, "fmi2DoStep(h = 100 s) = %d, want fmi2Discard", (int)st);
        CHECK(logged_discard > 0, "no logStatusDiscard message");
        CHECK(get_bool_status(c, fmi2Terminated, &terminated) == fmi2OK && !terminated,
              "fmi2Terminated after the discard");
        CHECK(get_real_status(c, fmi2LastSuccessfulTime, &last) == fmi2OK && last == STEPS * H,
              "fmi2LastSuccessfulTime = %.17g", last);
        CHECK(get_status(c, fmi2DoStepStatus, &st) == fmi2OK && st == fmi2Discard,
              "fmi2DoStepStatus = %d", (int)st);
        CHECK(set_state(c, before) == fmi2OK, "fmi2SetFMUstate after the discard");
        CHECK(do_step(c, STEPS * H, H, 1) == fmi2OK, "fmi2DoStep after the rollback");
        printf("discard: h = 100 s refused, fmi2Terminated = %d, last successful t = %g, rollback ok\n",
               terminated, last);
        CHECK(free_state_raw(c, &copy) == fmi2OK, "fmi2FreeFMUstate");
        CHECK(free_state_raw(c, &before) == fmi2OK, "fmi2FreeFMUstate");
        CHECK(terminate(c) == fmi2OK, "fmi2Terminate");
        free_instance(c);
    }
    /* no thread of the library may outlive its calls (it would run in unloaded code) */
    threads_after = thread_count();
    printf("threads of this process: %d before loading, %d after the run\n", threads_before,
           threads_after);
    CHECK(threads_before > 0 && threads_after == threads_before, "the library left threads behind");
    CHECK(lib_close(lib) == 0, "unloading the library");
    pause_ms(300);

    f = fopen(csv, "wb"); /* "\n" line ends on both platforms */
    if (!f) {
        printf("FAIL: cannot write %s\n", csv);
        return 2;
    }
    fprintf(f, "time");
    for (i = 0; i < m.n_out; i++) fprintf(f, ",%s", m.out[i].name);
    fprintf(f, "\n");
    for (k = 0; k < STEPS; k++) {
        fprintf(f, "%.17g", (k + 1) * H);
        for (i = 0; i < m.n_out; i++) fprintf(f, ",%.17g", hist[k][i]);
        fprintf(f, "\n");
    }
    fclose(f);
    printf("%s: %d rows to t = %g\n", csv, STEPS, STEPS * H);
    printf(failures ? "HOST: FAIL (%d)\n" : "HOST: OK\n", failures);
    return failures ? 1 : 0;
}

#ifndef _WIN32
/* Reads a history written by run(); returns the number of rows. */
static int read_csv(const char *path, char names[MAXV][128], int *cols, double rows[][MAXV + 1]) {
    char *text = read_file(path), *line, *save = NULL;
    int n = 0;
    if (!text) return -1;
    line = strtok_r(text, "\n", &save);
    *cols = 0;
    if (line) {
        char *tok, *s2 = NULL;
        for (tok = strtok_r(line, ",", &s2); tok && *cols < MAXV; tok = strtok_r(NULL, ",", &s2))
            snprintf(names[(*cols)++], 128, "%s", tok);
    }
    while ((line = strtok_r(NULL, "\n", &save)) && n < STEPS) {
        char *p = line;
        int j;
        for (j = 0; j < *cols && *p; j++) {
            rows[n][j] = strtod(p, &p);
            if (*p == ',') p++;
        }
        n++;
    }
    free(text);
    return n;
}

/* Compares history A (win64) with B (linux64). Strict: |a - b| <= 1e-12 * max(1, |b|) for every
 * value (tip positions within 1e-12 m). With SPREAD (B's binary run again with another libm,
 * see scripts/test-win64.sh) the gate per column is max(strict, factor * the largest
 * |spread - b| of that column), factor 10 for the tip columns (tip.*) and 100 for the others
 * (the support reaction is a residual and the most sensitive): A may differ from B no more
 * than B differs from itself when only the last bits of sin, cos, exp, ... change. Returns
 * non-zero if the gate fails, or if the strict test fails and `strict_gate` is set. */
#define TIP_FACTOR 10.0
#define OTHER_FACTOR 100.0
static int compare(const char *a_path, const char *b_path, const char *spread_path, int strict_gate) {
    static char na[MAXV][128], nb[MAXV][128], ns[MAXV][128];
    static double a[STEPS][MAXV + 1], b[STEPS][MAXV + 1], sp[STEPS][MAXV + 1];
    double spread[MAXV + 1] = {0};
    int ca, cb, cs = 0, ra = read_csv(a_path, na, &ca, a), rb = read_csv(b_path, nb, &cb, b);
    int i, k, identical = 0, strict_bad = 0, gate_bad = 0;
    double worst_ratio = 0;
    if (ra != STEPS || rb != STEPS || ca != cb || ca < 2) {
        printf("FAIL: %s has %d rows x %d columns, %s %d x %d (want %d rows, equal columns)\n",
               a_path, ra, ca, b_path, rb, cb, STEPS);
        return 1;
    }
    for (i = 1; i < ca; i++)
        if (strcmp(na[i], nb[i])) {
            printf("FAIL: column %d is %s in one file, %s in the other\n", i, na[i], nb[i]);
            return 1;
        }
    if (spread_path) {
        if (read_csv(spread_path, ns, &cs, sp) != STEPS || cs != cb) {
            printf("FAIL: cannot read %s\n", spread_path);
            return 1;
        }
        for (i = 0; i < ca; i++)
            for (k = 0; k < STEPS; k++) spread[i] = fmax(spread[i], fabs(sp[k][i] - b[k][i]));
    }
    for (k = 0; k < STEPS; k++) {
        int same = 1;
        for (i = 0; i < ca; i++) {
            double d = fabs(a[k][i] - b[k][i]), strict = 1e-12 * fmax(1.0, fabs(b[k][i]));
            double factor = strncmp(na[i], "tip.", 4) ? OTHER_FACTOR : TIP_FACTOR;
            double gate = fmax(strict, factor * spread[i]);
            if (memcmp(&a[k][i], &b[k][i], sizeof(double))) same = 0;
            if (!(d <= strict)) strict_bad++;
            if (spread[i] > 0 && !strncmp(na[i], "tip.", 4)) worst_ratio = fmax(worst_ratio, d / spread[i]);
            if (!(d <= gate) && gate_bad++ < 10)
                printf("FAIL row %d %s: %.17g vs %.17g (gate %.3g)\n", k, na[i], a[k][i], b[k][i], gate);
        }
        identical += same;
    }
    for (i = 1; i < ca; i++) {
        double worst = 0;
        for (k = 0; k < STEPS; k++) worst = fmax(worst, fabs(a[k][i] - b[k][i]));
        if (!strncmp(na[i], "tip.position.", 13))
            printf("max |diff| %s: %.3g m (spread of the linux64 binary with another libm: %.3g m)\n",
                   na[i], worst, spread[i]);
    }
    printf("compare: %d of %d rows bit-identical; strict 1e-12: %d values beyond (%s)",
           identical, STEPS, strict_bad, strict_bad ? "FAIL" : "pass");
    if (spread_path)
        printf("; libm-spread gate (tip x%g, others x%g): %d beyond (%s), worst tip |diff|/spread %.3g",
               TIP_FACTOR, OTHER_FACTOR, gate_bad, gate_bad ? "FAIL" : "pass", worst_ratio);
    printf("\n");
    return gate_bad || (strict_gate && strict_bad) ? 1 : 0;
}
#endif

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IONBF, 0);
#ifndef _WIN32
    if ((argc == 4 || argc == 5) && !strcmp(argv[1], "--compare"))
        return compare(argv[2], argv[3], argc == 5 ? argv[4] : NULL, getenv("WIN64_STRICT") != NULL);
#endif
    if (argc == 3) return run(argv[1], argv[2]);
    printf("usage: host FMU_DIR OUT.csv | host --compare A.csv B.csv\n");
    return 2;
}
