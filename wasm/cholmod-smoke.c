/* SPDX-License-Identifier: GPL-2.0-or-later
 *
 * cholmod-smoke.c: smoke test for the wasm CHOLMOD archive built by wasm/build-cholmod.sh (run it with --smoke).
 * Also builds natively against Debian's CHOLMOD: cc -O2 wasm/cholmod-smoke.c -I/usr/include/suitesparse -lcholmod -lm
 *
 * A = 2D 5-point Laplacian + I on a 60x60 grid (n = 3600, SPD), stored as its upper triangle.
 *  1. analyze + supernodal LL' factorization (exercises the BLAS/LAPACK: dsyrk, dgemm, dtrsm, dpotrf, ...),
 *     solve, residual check;
 *  2. cholmod_change_factor to simplicial LDL' (what update/downdate needs), rank-1 cholmod_updown with the
 *     single-entry column sqrt(w) e_i (entered in the permuted order, as cholmod_updown expects), solve, and compare
 *     with a fresh factorization of A + w e_i e_i';
 *  3. 100 update/downdate pairs on other entries (timing; the factor must come back to the same solution);
 *  4. METIS (cholmod_metis, METIS_NodeND) as the one ordering: CHOLMOD must report it selected METIS, the
 *     permutation must be a permutation, and the solve must agree with the AMD-ordered one.
 * Prints "cholmod-smoke OK" plus timings; exits non-zero on any failure.
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <cholmod.h>

#define GRID 60
#define TOL 1e-10

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int failures = 0;
static void check(int ok, const char *what, double value) {
  printf("  %-46s %.3e %s\n", what, value, ok ? "ok" : "FAILED");
  if (!ok) failures++;
}

/* upper triangle of (Laplacian + I) + w e_wi e_wi' (w = 0: none) */
static cholmod_sparse *make_matrix(int g, int wi, double w, cholmod_common *c) {
  int n = g * g;
  cholmod_triplet *T = cholmod_allocate_triplet(n, n, 3 * (size_t)n, 1, CHOLMOD_REAL, c);
  int *Ti = T->i, *Tj = T->j;
  double *Tx = T->x;
  size_t k = 0;
  for (int y = 0; y < g; y++)
    for (int x = 0; x < g; x++) {
      int p = y * g + x;
      Ti[k] = p; Tj[k] = p; Tx[k] = 5.0 + (p == wi ? w : 0.0); k++;
      if (x + 1 < g) { Ti[k] = p; Tj[k] = p + 1; Tx[k] = -1.0; k++; }
      if (y + 1 < g) { Ti[k] = p; Tj[k] = p + g; Tx[k] = -1.0; k++; }
    }
  T->nnz = k;
  cholmod_sparse *A = cholmod_triplet_to_sparse(T, 0, c);
  cholmod_free_triplet(&T, c);
  return A;
}

/* ||A x - b||_inf / ||b||_inf */
static double rel_residual(cholmod_sparse *A, cholmod_dense *x, cholmod_dense *b, cholmod_common *c) {
  cholmod_dense *r = cholmod_copy_dense(b, c);
  double one[2] = {1, 0}, mone[2] = {-1, 0};
  cholmod_sdmult(A, 0, mone, one, x, r, c); /* r = b - A x */
  double rn = cholmod_norm_dense(r, 0, c), bn = cholmod_norm_dense(b, 0, c);
  cholmod_free_dense(&r, c);
  return rn / bn;
}

static double rel_diff(cholmod_dense *x, cholmod_dense *y) {
  const double *a = x->x, *b = y->x;
  double d = 0, m = 0;
  for (size_t i = 0; i < x->nrow; i++) {
    d = fmax(d, fabs(a[i] - b[i]));
    m = fmax(m, fabs(b[i]));
  }
  return d / m;
}

/* single-entry column sqrt(w) e_i, in the permuted order of L (row k with Perm[k] == i) */
static cholmod_sparse *unit_column(cholmod_factor *L, int i, double w, cholmod_common *c) {
  int n = (int)L->n, k = -1;
  const int *Perm = L->Perm;
  for (int q = 0; q < n; q++)
    if (Perm[q] == i) { k = q; break; }
  cholmod_sparse *C = cholmod_allocate_sparse(n, 1, 1, 1, 1, 0, CHOLMOD_REAL, c);
  int *Cp = C->p, *Ci = C->i;
  double *Cx = C->x;
  Cp[0] = 0; Cp[1] = 1; Ci[0] = k; Cx[0] = sqrt(w);
  return C;
}

int main(void) {
  cholmod_common common, *c = &common;
  cholmod_start(c);
  c->supernodal = CHOLMOD_SUPERNODAL;
  const int n = GRID * GRID, wi = n / 2 + GRID / 3;
  const double w = 2.5;
  double t;

  printf("cholmod-smoke: CHOLMOD %d.%d.%d, n = %d (%dx%d grid Laplacian + I)\n", CHOLMOD_MAIN_VERSION,
         CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION, n, GRID, GRID);

  cholmod_sparse *A = make_matrix(GRID, -1, 0, c);
  cholmod_dense *b = cholmod_zeros(n, 1, CHOLMOD_REAL, c);
  for (int i = 0; i < n; i++) ((double *)b->x)[i] = 1.0 + (i % 7) * 0.25 - (i % 3) * 0.5;

  /* 1. supernodal */
  t = now_ms();
  cholmod_factor *L = cholmod_analyze(A, c);
  double t_analyze = now_ms() - t;
  t = now_ms();
  int ok_fact = L && cholmod_factorize(A, L, c);
  double t_factor = now_ms() - t;
  if (!ok_fact || c->status != CHOLMOD_OK) {
    printf("factorization failed (status %d)\n", c->status);
    return 1;
  }
  check(L->is_super && L->is_ll, "factor is supernodal LL' (is_super)", (double)L->is_super);
  t = now_ms();
  cholmod_dense *x = cholmod_solve(CHOLMOD_A, L, b, c);
  double t_solve = now_ms() - t;
  check(rel_residual(A, x, b, c) < TOL, "supernodal: ||Ax-b||/||b||", rel_residual(A, x, b, c));

  /* 2. simplicial LDL', rank-1 update */
  t = now_ms();
  int ok_change = cholmod_change_factor(CHOLMOD_REAL, 0 /* LDL' */, 0 /* simplicial */, 0 /* unpacked */,
                                        1 /* monotonic */, L, c);
  double t_change = now_ms() - t;
  check(ok_change && !L->is_super && !L->is_ll, "change_factor -> simplicial LDL'", (double)ok_change);

  cholmod_sparse *C = unit_column(L, wi, w, c);
  t = now_ms();
  int ok_up = cholmod_updown(1, C, L, c);
  double t_updown = now_ms() - t;
  check(ok_up, "cholmod_updown(+, sqrt(w) e_i)", (double)ok_up);
  cholmod_dense *x_up = cholmod_solve(CHOLMOD_A, L, b, c);

  cholmod_sparse *A2 = make_matrix(GRID, wi, w, c);
  cholmod_factor *L2 = cholmod_analyze(A2, c);
  cholmod_factorize(A2, L2, c);
  cholmod_dense *x_fresh = cholmod_solve(CHOLMOD_A, L2, b, c);
  check(rel_residual(A2, x_up, b, c) < TOL, "updated: ||(A+w e_i e_i')x-b||/||b||", rel_residual(A2, x_up, b, c));
  check(rel_diff(x_up, x_fresh) < TOL, "updated vs fresh factorization (rel diff)", rel_diff(x_up, x_fresh));

  /* 3. 100 update/downdate pairs; the solution must not move */
  const int pairs = 100;
  t = now_ms();
  for (int r = 0; r < pairs; r++) {
    cholmod_sparse *Cr = unit_column(L, (r * 37 + 11) % n, 0.5 + r % 5, c);
    cholmod_updown(1, Cr, L, c);
    cholmod_updown(0, Cr, L, c);
    cholmod_free_sparse(&Cr, c);
  }
  double t_pairs = (now_ms() - t) / (2.0 * pairs);
  check(c->status == CHOLMOD_OK, "100 update/downdate pairs: status", (double)c->status);
  cholmod_dense *x_after = cholmod_solve(CHOLMOD_A, L, b, c);
  check(rel_diff(x_after, x_fresh) < TOL, "after 100 pairs vs fresh (rel diff)", rel_diff(x_after, x_fresh));

  /* 4. METIS ordering (Partition module) */
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_METIS;
  t = now_ms();
  cholmod_factor *Lm = cholmod_analyze(A2, c);
  double t_metis = now_ms() - t;
  check(Lm && c->selected == 0 && c->method[0].ordering == CHOLMOD_METIS && Lm->ordering == CHOLMOD_METIS,
        "METIS ordering selected (L->ordering)", Lm ? (double)Lm->ordering : -1.0);
  int *seen = calloc(n, sizeof(int)), perm_ok = Lm != NULL;
  for (int k = 0; perm_ok && k < n; k++) {
    const int p = ((int *)Lm->Perm)[k];
    perm_ok = p >= 0 && p < n && !seen[p]++;
  }
  free(seen);
  check(perm_ok, "METIS: Perm is a permutation", (double)perm_ok);
  cholmod_factorize(A2, Lm, c);
  cholmod_dense *x_metis = cholmod_solve(CHOLMOD_A, Lm, b, c);
  check(rel_diff(x_metis, x_fresh) < TOL, "METIS vs AMD ordering solve (rel diff)", rel_diff(x_metis, x_fresh));
  const double lnz_metis = c->lnz;
  cholmod_free_dense(&x_metis, c);
  cholmod_free_factor(&Lm, c);

  printf("  timings (ms): analyze %.2f, supernodal factor %.2f, solve %.2f, change_factor %.2f,\n"
         "                updown %.3f (first), %.3f (avg of %d)\n",
         t_analyze, t_factor, t_solve, t_change, t_updown, t_pairs, 2 * pairs);
  printf("  METIS analyze %.2f ms, nnz(L) = %.0f\n", t_metis, lnz_metis);

  cholmod_free_dense(&x_after, c);
  cholmod_free_dense(&x_fresh, c);
  cholmod_free_factor(&L2, c);
  cholmod_free_sparse(&A2, c);
  cholmod_free_dense(&x_up, c);
  cholmod_free_sparse(&C, c);
  cholmod_free_dense(&x, c);
  cholmod_free_factor(&L, c);
  cholmod_free_dense(&b, c);
  cholmod_free_sparse(&A, c);
  cholmod_finish(c);
  check(c->malloc_count == 0, "malloc_count after cholmod_finish", (double)c->malloc_count);

  if (failures) {
    printf("cholmod-smoke FAILED (%d checks)\n", failures);
    return 1;
  }
  printf("cholmod-smoke OK\n");
  return 0;
}
