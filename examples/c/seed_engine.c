/* The seed engine (Part III) in C, in float like the seed, as an external dropcheck engine.
 *
 * Speaks docs/protocol.md on stdin/stdout; no dependencies beyond the C library (POSIX getline).
 * Per step and dynamic body, in exactly the order of ours/physics.hpp, every operation in float:
 *     v += g*h;  v += (F/m)*h;  v *= phi;  x += v*h        (law "after-forces")
 * Build without FMA contraction (-ffp-contract=off) so float results match the compiled `ours`.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int is_static;
  float mass, x[3], v[3];
} Body;

static Body* bodies = NULL;
static int body_count = 0;
static int next_body = 0; /* the next "body" line fills bodies[next_body] */
static float g[3], h, phi;

static void reply(const char* line) {
  fputs(line, stdout);
  fputc('\n', stdout);
  fflush(stdout);
}

/* "state N" and x y z vx vy vz per body. Each float goes out as the double it converts to, with
 * %.17g: that decimal reads back as exactly that double (%.9g would read back as a nearby double). */
static void reply_state(const char* step) {
  printf("state %s", step);
  for (int i = 0; i < body_count; ++i)
    for (int k = 0; k < 6; ++k) printf(" %.17g", (double)(k < 3 ? bodies[i].x[k] : bodies[i].v[k - 3]));
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
  } else if (strcmp(word, "h") == 0) {
    read_floats(rest, &h, 1);
  } else if (strcmp(word, "gravity") == 0) {
    read_floats(rest, g, 3);
  } else if (strcmp(word, "damping") == 0) {
    float k_phi[2];
    read_floats(rest, k_phi, 2);
    phi = k_phi[1];
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
    float n[10];
    read_floats(rest + (b->is_static ? 6 : 7), n, 10);
    b->mass = n[0];
    memcpy(b->x, n + 4, sizeof b->x);
    memcpy(b->v, n + 7, sizeof b->v);
  } else if (strcmp(word, "end") == 0) {
    reply_state("0");
  } else if (strcmp(word, "step") == 0) {
    char* end;
    const long n = strtol(rest, &end, 10);
    for (int i = 0; i < body_count; ++i) {
      float f[3];
      end = (char*)read_floats(end, f, 3);
      step_body(&bodies[i], f);
    }
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
  reply("capabilities");
  reply("ready");
  char* line = NULL;
  size_t size = 0;
  while (getline(&line, &size, stdin) > 0)
    if (!handle(line)) break;
  free(line);
  free(bodies);
  return 0;
}
