/* poisson_dct.c: the direct DCT solve of the unweighted screened Poisson system
 * (recon/poisson_ops.h, RESTIR_POISSON_DCT of restir/poisson.h) and the cache of its FFTW plans.
 *
 * The Neumann grid Laplacian is Lx (+) Ly with Lx the path-graph Laplacian of w nodes, whose
 * eigenvectors cos(pi k (i + 1/2) / w) are the DCT-II basis, eigenvalue 2 - 2 cos(pi k / w).
 * FFTW's REDFT10 (DCT-II) followed by REDFT01 (DCT-III) multiplies by 2w per dimension, hence
 * the 1 / (4 w h). Channels are planar copies so one plan pair serves all three.
 *
 * Plans. FFTW's planner is not thread-safe and planning costs more than a small solve, so the
 * plans of the last DCT_PLAN_SLOTS image sizes are kept. Planning, lookups and destruction happen
 * under one mutex; a solve holds a reference to its plans while it executes them
 * (fftw_execute_r2r on fftw_malloc arrays of the plan's alignment, which FFTW allows from any
 * thread), and only plans nobody holds are ever destroyed. When every slot is held by a running
 * solve of another size, the call plans privately (still under the mutex) and destroys its plans
 * afterwards. FFTW_ESTIMATE plans of one size are the same plans every time, so caching does not
 * change a bit of the result. */
#include <math.h>
#include <stdlib.h>

#include "recon/poisson_ops.h"
#include "restir/poisson.h"

#ifdef RESTIR_HAVE_FFTW
#include <fftw3.h>
#include <pthread.h>

#define DCT_PLAN_SLOTS 8

struct dct_plans {
    int w, h;
    int users;               /* solves executing these plans now */
    unsigned long last_used; /* for evicting the least recently used free slot */
    fftw_plan fwd, inv;
};

static pthread_mutex_t plan_lock = PTHREAD_MUTEX_INITIALIZER;
static struct dct_plans plan_cache[DCT_PLAN_SLOTS];
static unsigned long plan_clock;

static void plans_destroy(struct dct_plans *p)
{
    if (p->fwd)
        fftw_destroy_plan(p->fwd);
    if (p->inv)
        fftw_destroy_plan(p->inv);
    p->fwd = p->inv = NULL;
    p->w = p->h = 0;
}

static int plans_make(struct dct_plans *p, int w, int h, double *array)
{
    p->fwd = fftw_plan_r2r_2d(h, w, array, array, FFTW_REDFT10, FFTW_REDFT10, FFTW_ESTIMATE);
    p->inv = fftw_plan_r2r_2d(h, w, array, array, FFTW_REDFT01, FFTW_REDFT01, FFTW_ESTIMATE);
    if (!p->fwd || !p->inv) {
        plans_destroy(p);
        return -1;
    }
    p->w = w;
    p->h = h;
    return 0;
}

/* The plans for a w x h solve: a cached slot (*slot set, its reference taken) or, when every slot
 * is held, private plans in *own (*slot NULL). array: an fftw_malloc array of w h doubles. */
static int plans_acquire(int w, int h, double *array, struct dct_plans **slot, struct dct_plans *own)
{
    *slot = NULL;
    int rc = -1;
    pthread_mutex_lock(&plan_lock);
    struct dct_plans *free_slot = NULL;
    for (int i = 0; i < DCT_PLAN_SLOTS; i++) {
        struct dct_plans *p = &plan_cache[i];
        if (p->fwd && p->w == w && p->h == h) {
            free_slot = p;
            break;
        }
        if (p->users == 0 && (!free_slot || !p->fwd || (free_slot->fwd && p->last_used < free_slot->last_used)))
            free_slot = p;
    }
    if (free_slot && !(free_slot->fwd && free_slot->w == w && free_slot->h == h)) {
        plans_destroy(free_slot);
        if (plans_make(free_slot, w, h, array) != 0)
            free_slot = NULL;
    }
    if (free_slot) {
        free_slot->users++;
        free_slot->last_used = ++plan_clock;
        *slot = free_slot;
        *own = *free_slot;
        rc = 0;
    } else {
        own->fwd = own->inv = NULL;
        rc = plans_make(own, w, h, array);
    }
    pthread_mutex_unlock(&plan_lock);
    return rc;
}

static void plans_release(struct dct_plans *slot, struct dct_plans *own)
{
    pthread_mutex_lock(&plan_lock);
    if (slot)
        slot->users--;
    else
        plans_destroy(own);
    pthread_mutex_unlock(&plan_lock);
}

int restir_poisson_has_dct(void)
{
    return 1;
}

void restir_poisson_release_plans(void)
{
    pthread_mutex_lock(&plan_lock);
    for (int i = 0; i < DCT_PLAN_SLOTS; i++)
        if (plan_cache[i].users == 0)
            plans_destroy(&plan_cache[i]);
    pthread_mutex_unlock(&plan_lock);
}

int restir_rp_dct_solve(int w, int h, double a2, const double *b, double *x)
{
    const size_t n = (size_t)w * (size_t)h;
    double *ch[3] = {fftw_alloc_real(n), fftw_alloc_real(n), fftw_alloc_real(n)};
    double *lx = restir_rp_alloc((size_t)w), *ly = restir_rp_alloc((size_t)h);
    struct dct_plans *slot = NULL, plans = {0};
    int rc = -1, have_plans = 0;
    if (!ch[0] || !ch[1] || !ch[2] || !lx || !ly)
        goto done;
    if (plans_acquire(w, h, ch[0], &slot, &plans) != 0)
        goto done;
    have_plans = 1;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < w; i++)
        lx[i] = 2.0 - 2.0 * cos(pi * i / w);
    for (int j = 0; j < h; j++)
        ly[j] = 2.0 - 2.0 * cos(pi * j / h);
    const long ln = (long)n;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (long k = 0; k < ln; k++)
        for (int c = 0; c < 3; c++)
            ch[c][k] = b[3 * k + c];
#pragma omp parallel for schedule(static, 1) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int c = 0; c < 3; c++)
        fftw_execute_r2r(plans.fwd, ch[c], ch[c]);
    const double norm = 4.0 * (double)n;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const double f = 1.0 / ((a2 + lx[i] + ly[j]) * norm);
            const size_t k = (size_t)j * (size_t)w + (size_t)i;
            for (int c = 0; c < 3; c++)
                ch[c][k] *= f;
        }
    }
#pragma omp parallel for schedule(static, 1) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int c = 0; c < 3; c++)
        fftw_execute_r2r(plans.inv, ch[c], ch[c]);
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (long k = 0; k < ln; k++)
        for (int c = 0; c < 3; c++)
            x[3 * k + c] = ch[c][k];
    rc = 0;
done:
    if (have_plans)
        plans_release(slot, &plans);
    for (int c = 0; c < 3; c++)
        fftw_free(ch[c]);
    free(lx);
    free(ly);
    return rc;
}

#else /* librestir built without FFTW: the DCT solve is not there (restir/poisson.h) */

int restir_poisson_has_dct(void)
{
    return 0;
}

void restir_poisson_release_plans(void) {}

int restir_rp_dct_solve(int w, int h, double a2, const double *b, double *x)
{
    (void)w, (void)h, (void)a2, (void)b, (void)x;
    return -1;
}

#endif
