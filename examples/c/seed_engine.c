/* The seed engine (Part III) in C, in float like the seed, as an external dropcheck engine.
 *
 * Speaks docs/protocol.md on stdin/stdout; no dependencies beyond the C library (POSIX getline).
 * Per step and dynamic body, in exactly the order of ours/physics.hpp, every operation in float:
 *     v += g*h;  v += (F/m)*h;  v *= phi;  x += v*h        (law "after-forces")
 * Build without FMA contraction (-ffp-contract=off) so float results match the compiled `ours`.
 * It turns bodies too, by the rotational member "explicit/first-order" (ours's IntegrateAngularForce),
 * with R the rotation of q and I the principal moments:
 *     w += R*((R^T*(tau - w x (R*(I .* (R^T*w))))) ./ I)*h;  w *= phi_a;
 *     q = normalize(q + (h/2)*(0, w)*q)
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int is_static;
  float mass, x[3], v[3];
  float q[4], w[3], inertia[3]; /* q = (w, x, y, z); w in the world frame; rotating scenes */
} Body;

static Body* bodies = NULL;
static int body_count = 0;
static int next_body = 0; /* the next "body" line fills bodies[next_body] */
static float g[3], h, phi;
static float phi_a = 1.0f;
static int rotating = 0; /* the scene sent "angular-damping": bodies, steps and states turn */

static void reply(const char* line) {
  fputs(line, stdout);
  fputc('\n', stdout);
  fflush(stdout);
}

/* "state N" and x y z vx vy vz per body. Each float goes out as the double it converts to, with
 * %.17g: that decimal reads back as exactly that double (%.9g would read back as a nearby double). */
static void reply_state(const char* step) {
  printf("state %s", step);
  for (int i = 0; i < body_count; ++i) {
    const Body* b = &bodies[i];
    for (int k = 0; k < 6; ++k) printf(" %.17g", (double)(k < 3 ? b->x[k] : b->v[k - 3]));
    if (rotating)
      for (int k = 0; k < 7; ++k) printf(" %.17g", (double)(k < 4 ? b->q[k] : b->w[k - 4]));
  }
  reply("");
}

/* Reads `n` floats (as doubles, then rounded to float like the f32 adapter) from `s`. */
static const char* read_floats(const char* s, float* out, int n) {
  for (int i = 0; i < n; ++i) {
    char* end;
    out[i] = (float)strtod(s, &end);
    s = end;
  }
  return s;
}

static void step_body(Body* b, const float f[3]) {
  if (b->is_static) return;
  for (int i = 0; i < 3; ++i) b->v[i] += g[i] * h;
  for (int i = 0; i < 3; ++i) b->v[i] += (f[i] / b->mass) * h;
  for (int i = 0; i < 3; ++i) b->v[i] *= phi;
  for (int i = 0; i < 3; ++i) b->x[i] += b->v[i] * h;
}

/* The rotation matrix of the unit quaternion q = (w, x, y, z). */
static void rotation(const float q[4], float r[3][3]) {
  const float w = q[0], x = q[1], y = q[2], z = q[3];
  r[0][0] = 1 - 2 * (y * y + z * z), r[0][1] = 2 * (x * y - w * z), r[0][2] = 2 * (x * z + w * y);
  r[1][0] = 2 * (x * y + w * z), r[1][1] = 1 - 2 * (x * x + z * z), r[1][2] = 2 * (y * z - w * x);
  r[2][0] = 2 * (x * z - w * y), r[2][1] = 2 * (y * z + w * x), r[2][2] = 1 - 2 * (x * x + y * y);
}

/* out = r*v, or r^T*v when `transposed`. */
static void times(float r[3][3], const float v[3], float out[3], int transposed) {
  for (int i = 0; i < 3; ++i) {
    out[i] = 0;
    for (int j = 0; j < 3; ++j) out[i] += (transposed ? r[j][i] : r[i][j]) * v[j];
  }
}

/* One step of the explicit/first-order rotational member. */
static void turn_body(Body* b, const float tau[3]) {
  if (b->is_static) return;
  float* w = b->w;
  if (w[0] == 0 && w[1] == 0 && w[2] == 0 && tau[0] == 0 && tau[1] == 0 && tau[2] == 0) return;
  float r[3][3], wb[3], lb[3], l[3], net[3], nb[3], dw[3];
  rotation(b->q, r);
  times(r, w, wb, 1);
  for (int i = 0; i < 3; ++i) lb[i] = b->inertia[i] * wb[i];
  times(r, lb, l, 0);
  net[0] = tau[0] - (w[1] * l[2] - w[2] * l[1]);
  net[1] = tau[1] - (w[2] * l[0] - w[0] * l[2]);
  net[2] = tau[2] - (w[0] * l[1] - w[1] * l[0]);
  times(r, net, nb, 1);
  for (int i = 0; i < 3; ++i) nb[i] /= b->inertia[i];
  times(r, nb, dw, 0);
  for (int i = 0; i < 3; ++i) w[i] = (w[i] + dw[i] * h) * phi_a;
  float* q = b->q; /* q += (h/2)*(0, w)*q, then normalise */
  const float s[4] = {-(w[0] * q[1] + w[1] * q[2] + w[2] * q[3]),
                      w[0] * q[0] + w[1] * q[3] - w[2] * q[2],
                      w[1] * q[0] + w[2] * q[1] - w[0] * q[3],
                      w[2] * q[0] + w[0] * q[2] - w[1] * q[1]};
  for (int i = 0; i < 4; ++i) q[i] += s[i] * (h / 2);
  const float norm = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int i = 0; i < 4; ++i) q[i] /= norm;
}

/* Handles one request line; returns 0 on "quit". */
static int handle(char* line) {
  char word[16] = "";
  if (sscanf(line, "%15s", word) != 1) return 1;
  const char* rest = line + strlen(word);
  if (strcmp(word, "scene") == 0) {
    body_count = atoi(rest);
    free(bodies);
    bodies = calloc((size_t)(body_count > 0 ? body_count : 1), sizeof(Body));
    next_body = 0;
    rotating = 0;
    phi_a = 1.0f;
  } else if (strcmp(word, "h") == 0) {
    read_floats(rest, &h, 1);
  } else if (strcmp(word, "gravity") == 0) {
    read_floats(rest, g, 3);
  } else if (strcmp(word, "damping") == 0) {
    float k_phi[2];
    read_floats(rest, k_phi, 2);
    phi = k_phi[1];
  } else if (strcmp(word, "angular-damping") == 0) { /* a rotating scene */
    float k_phi[2];
    read_floats(rest, k_phi, 2);
    phi_a = k_phi[1];
    rotating = 1;
  } else if (strcmp(word, "contacts") == 0) {
    if (atoi(rest) != 0) reply("error contacts are not supported (free flight only)");
  } else if (strcmp(word, "body") == 0) {
    if (next_body >= body_count) {
      reply("error more body lines than the scene announced");
      return 1;
    }
    Body* b = &bodies[next_body++];
    while (*rest == ' ') ++rest;
    b->is_static = strncmp(rest, "static", 6) == 0;
    float n[20];
    read_floats(rest + (b->is_static ? 6 : 7), n, rotating ? 20 : 10);
    b->mass = n[0];
    memcpy(b->x, n + 4, sizeof b->x);
    memcpy(b->v, n + 7, sizeof b->v);
    if (rotating) {
      memcpy(b->q, n + 10, sizeof b->q);
      memcpy(b->w, n + 14, sizeof b->w);
      memcpy(b->inertia, n + 17, sizeof b->inertia);
    }
  } else if (strcmp(word, "end") == 0) {
    reply_state("0");
  } else if (strcmp(word, "step") == 0) {
    char* end;
    const long n = strtol(rest, &end, 10);
    float* f = calloc((size_t)(6 * (body_count > 0 ? body_count : 1)), sizeof(float));
    /* forces, 3 per body; then, in a rotating scene, torques, 3 per body */
    read_floats(end, f, (rotating ? 6 : 3) * body_count);
    for (int i = 0; i < body_count; ++i) {
      step_body(&bodies[i], f + 3 * i);
      if (rotating) turn_body(&bodies[i], f + 3 * (body_count + i));
    }
    free(f);
    char step[32];
    snprintf(step, sizeof step, "%ld", n);
    reply_state(step);
  } else if (strcmp(word, "quit") == 0) {
    return 0;
  } else {
    printf("error unknown request %s\n", word);
    fflush(stdout);
  }
  return 1;
}

int main(void) {
  reply("dropcheck-engine 1");
  reply("name seed-c");
  reply("version 1.0");
  reply("scalar f32");
  reply("law after-forces");
  reply("capabilities rotation");
  reply("rotation-law explicit/first-order");
  reply("ready");
  char* line = NULL;
  size_t size = 0;
  while (getline(&line, &size, stdin) > 0)
    if (!handle(line)) break;
  free(line);
  free(bodies);
  return 0;
}
