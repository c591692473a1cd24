/*
 * page_turn.c: turns one page of a Folio book through the C API and checks the result.
 *
 * The right block's top page is grabbed near its fore-edge, carried over the spine along a
 * smooth arc in DRAG_STEPS steps, released, and stepped until it has merged into a block
 * (at most MAX_SETTLE_STEPS steps). The render mesh is then copied out (size query first)
 * and checked. Exits 0 when the page lies on the left block, every mesh value is finite and
 * the DOG residual stayed small; 1 otherwise.
 *
 * Usage: page_turn [f32|f64]   (default f64)
 * Build: see README.md in this directory (C11, links libfolio_capi.a).
 */
#include "folio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Drag steps over the spine (one time step of 1/60 s each). */
#define DRAG_STEPS 100
/* Most steps after the release before the page must have merged. */
#define MAX_SETTLE_STEPS 600
/* Largest DOG residual accepted during the turn (dimensionless). */
#define DOG_LIMIT 0.05

/* Prints the failed call, its status and the library's message for this thread. */
static void report_failure(const char *call, FolioStatus status) {
    char message[512];
    size_t needed = 0;
    FolioStatus got = folio_last_error_message(message, sizeof message, &needed);
    fprintf(stderr, "%s: %s: %s%s\n", call, folio_status_name(status), message,
            got == FOLIO_STATUS_BUFFER_TOO_SMALL ? " [truncated]" : "");
}

/* Runs a call; on failure reports it and jumps to the cleanup. */
#define CHECK(call)                                                                          \
    do {                                                                                     \
        FolioStatus check_status_ = (call);                                                  \
        if (check_status_ != FOLIO_STATUS_OK) {                                              \
            report_failure(#call, check_status_);                                            \
            goto done;                                                                       \
        }                                                                                    \
    } while (0)

/* The finger's path: from the held point `start` over the spine to its mirror image, on
 * phi = pi * smoothstep(s), s in [0, 1]:
 *   x = x0 (1 - 0.1 sin phi) cos phi,  y = y0 + 0.7 x0 sin phi,  z = z0 + 0.12 H sin phi. */
static void finger(const double start[3], double height, int k, double out[3]) {
    const double pi = 3.14159265358979323846;
    double s = (double)k / (double)(DRAG_STEPS - 1);
    double phi = pi * s * s * (3.0 - 2.0 * s);
    out[0] = start[0] * (1.0 - 0.1 * sin(phi)) * cos(phi);
    out[1] = start[1] + 0.7 * start[0] * sin(phi);
    out[2] = start[2] + 0.12 * height * sin(phi);
}

static int all_finite(const float *v, size_t n) {
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(v[i])) {
            return 0;
        }
    }
    return 1;
}

static double max_d(double a, double b) { return a > b ? a : b; }

int main(int argc, char **argv) {
    int ok = 0;
    FolioBookHandle book = {0};
    float *positions = NULL, *normals = NULL, *uvs = NULL;
    uint32_t *indices = NULL;
    FolioBookSettings settings;
    FolioStepReport report;
    memset(&report, 0, sizeof report);

    if (folio_api_version() != FOLIO_API_VERSION) {
        fprintf(stderr, "library API version %u, header %u\n", (unsigned)folio_api_version(),
                (unsigned)FOLIO_API_VERSION);
        return 1;
    }
    CHECK(folio_book_settings_default(&settings));
    if (argc > 1 && strcmp(argv[1], "f32") == 0) {
        settings.precision = FOLIO_PRECISION_F32;
    } else if (argc > 1 && strcmp(argv[1], "f64") != 0) {
        fprintf(stderr, "usage: %s [f32|f64]\n", argv[0]);
        return 2;
    }
    const double width = settings.page_width;
    const double height = settings.page_width * settings.aspect_ratio;
    CHECK(folio_book_create(&settings, &book));

    /* Grab the right page by its fore-edge, a fifth of the way up, and turn it. */
    CHECK(folio_book_grab(book, FOLIO_SIDE_RIGHT, width, 0.2 * height, 1));
    double start[3];
    CHECK(folio_book_held_position(book, start));
    double dog_max = 0.0, stretch_max = 0.0, penetration_max = 0.0;
    uint32_t kkt_unknowns = 0, kkt_rows = 0, stalled = 0;
    for (int k = 0; k < DRAG_STEPS; k++) {
        double p[3];
        finger(start, height, k, p);
        CHECK(folio_book_drag(book, p[0], p[1], p[2]));
        CHECK(folio_book_step(book, &report));
        if (report.status != FOLIO_STEP_STATUS_CONVERGED &&
            report.status != FOLIO_STEP_STATUS_ITERATION_LIMIT) {
            stalled++;
        }
        dog_max = max_d(dog_max, report.dog_residual);
        stretch_max = max_d(stretch_max, report.stretch_max);
        penetration_max = max_d(penetration_max, report.penetration);
        kkt_unknowns = report.kkt_unknowns;
        kkt_rows = report.kkt_rows;
    }
    CHECK(folio_book_release(book));
    int settle = 0;
    while (settle < MAX_SETTLE_STEPS && report.merged == FOLIO_SIDE_NONE) {
        CHECK(folio_book_step(book, &report));
        settle++;
        if (report.has_active_page) {
            dog_max = max_d(dog_max, report.dog_residual);
            penetration_max = max_d(penetration_max, report.penetration);
        }
    }

    /* The render mesh: sizes first, then the copy. */
    uint32_t vertices = 0, triangles = 0;
    CHECK(folio_book_mesh_size(book, &vertices, &triangles));
    positions = malloc(3 * (size_t)vertices * sizeof *positions);
    normals = malloc(3 * (size_t)vertices * sizeof *normals);
    uvs = malloc(2 * (size_t)vertices * sizeof *uvs);
    indices = malloc(3 * (size_t)triangles * sizeof *indices);
    if (!positions || !normals || !uvs || !indices) {
        fprintf(stderr, "out of memory\n");
        goto done;
    }
    CHECK(folio_book_mesh_copy(book, positions, 3 * (size_t)vertices, normals,
                               3 * (size_t)vertices, uvs, 2 * (size_t)vertices, indices,
                               3 * (size_t)triangles));
    int finite = all_finite(positions, 3 * (size_t)vertices) &&
                 all_finite(normals, 3 * (size_t)vertices) && all_finite(uvs, 2 * (size_t)vertices);
    int indices_ok = 1;
    for (size_t i = 0; i < 3 * (size_t)triangles; i++) {
        indices_ok &= indices[i] < vertices;
    }
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < vertices; v++) {
        for (int a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], positions[3 * v + a]);
            hi[a] = fmaxf(hi[a], positions[3 * v + a]);
        }
    }

    const uint32_t right_before = settings.total_pages - settings.left_pages;
    int merged_left = report.merged == FOLIO_SIDE_LEFT &&
                      report.pages_left == settings.left_pages + 1 &&
                      report.pages_right == right_before - 1 && report.pages_active == 0;
    printf("folio C API v%u, %s book of %u pages (%u left, %u right)\n",
           (unsigned)folio_api_version(),
           settings.precision == FOLIO_PRECISION_F32 ? "f32" : "f64",
           (unsigned)settings.total_pages, (unsigned)settings.left_pages,
           (unsigned)right_before);
    printf("grabbed at (%.2f, %.2f, %.2f), dragged %d steps, KKT %u unknowns x %u rows\n",
           start[0], start[1], start[2], DRAG_STEPS, (unsigned)kkt_unknowns,
           (unsigned)kkt_rows);
    printf("released; merged into the %s block after %d steps: pages %u left, %u right\n",
           report.merged == FOLIO_SIDE_LEFT    ? "left"
           : report.merged == FOLIO_SIDE_RIGHT ? "right"
                                               : "(no)",
           settle, (unsigned)report.pages_left, (unsigned)report.pages_right);
    printf("max DOG residual %.2e, max stretch %.4f, max penetration %.2e, stalled steps %u\n",
           dog_max, stretch_max, penetration_max, (unsigned)stalled);
    printf("mesh: %u vertices, %u triangles, x [%.2f, %.2f] y [%.2f, %.2f] z [%.2f, %.2f]\n",
           (unsigned)vertices, (unsigned)triangles, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);

    ok = merged_left && finite && indices_ok && dog_max < DOG_LIMIT;
    printf("checks: merged left %s, finite mesh %s, indices %s, DOG residual < %.2g %s\n",
           merged_left ? "ok" : "FAILED", finite ? "ok" : "FAILED", indices_ok ? "ok" : "FAILED",
           DOG_LIMIT, dog_max < DOG_LIMIT ? "ok" : "FAILED");

done:
    free(positions);
    free(normals);
    free(uvs);
    free(indices);
    if (book.id != 0) {
        if (folio_book_destroy(book) != FOLIO_STATUS_OK) {
            ok = 0;
        }
        /* The handle is stale now: the library says so instead of touching freed memory. */
        FolioStatus again = folio_book_step(book, &report);
        if (again != FOLIO_STATUS_STALE_HANDLE) {
            fprintf(stderr, "step after destroy: %s\n", folio_status_name(again));
            ok = 0;
        }
    }
    printf("%s\n", ok ? "page turn: ok" : "page turn: FAILED");
    return ok ? 0 : 1;
}
