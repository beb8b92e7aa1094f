/* SPDX-License-Identifier: BSD-3-Clause */
/* Which of the C library's elementary functions round differently from one glibc to another: a
 * hash of each function's results over 4e6 fixed inputs. Build it once for the oldest glibc (Zig:
 * `python -m ziglang cc -target x86_64-linux-gnu.2.28 -O1 -fno-builtin libm_survey.c -lm`) and run
 * it with each release's own loader and libm, no chroot needed:
 *   DIR/lib64/ld-linux-x86-64.so.2 --library-path DIR/lib/x86_64-linux-gnu ./a.out
 * (Debian 11: DIR/lib/x86_64-linux-gnu/ld-2.31.so). Lines that differ name the functions that
 * changed (docs/BUILDING.md "The same bits on every glibc"). */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <string.h>
static uint64_t st = 88172645463325252ull;
static uint64_t rnd(void){ st ^= st << 13; st ^= st >> 7; st ^= st << 17; return st; }
static double u01(void){ return (rnd() >> 11) * (1.0/9007199254740992.0); }
static uint64_t h;
static void mixf(float f){ uint32_t b; memcpy(&b,&f,4); h = (h ^ b) * 1099511628211ull; }
static void mixd(double f){ uint64_t b; memcpy(&b,&f,8); h = (h ^ b) * 1099511628211ull; }
#define N 4000000
#define F1(name, expr, lo, hi) { h=1469598103934665603ull; st=88172645463325252ull; for(int i=0;i<N;i++){ float x=(float)(lo+(hi-lo)*u01()); mixf(expr);} printf("%-8s %016llx\n", name, (unsigned long long)h); }
#define F2(name, expr, lo, hi) { h=1469598103934665603ull; st=88172645463325252ull; for(int i=0;i<N;i++){ float x=(float)(lo+(hi-lo)*u01()); float y=(float)(lo+(hi-lo)*u01()); mixf(expr);} printf("%-8s %016llx\n", name, (unsigned long long)h); }
#define D1(name, expr, lo, hi) { h=1469598103934665603ull; st=88172645463325252ull; for(int i=0;i<N;i++){ double x=(lo+(hi-lo)*u01()); mixd(expr);} printf("%-8s %016llx\n", name, (unsigned long long)h); }
#define D2(name, expr, lo, hi) { h=1469598103934665603ull; st=88172645463325252ull; for(int i=0;i<N;i++){ double x=(lo+(hi-lo)*u01()); double y=(lo+(hi-lo)*u01()); mixd(expr);} printf("%-8s %016llx\n", name, (unsigned long long)h); }
int main(void){
  F1("acosf", acosf(x), -1, 1)
  F2("atan2f", atan2f(y,x), -1e-2, 1e-2)
  F1("erfcf", erfcf(x), -6, 6)
  F1("expf", expf(x), -60, 1)
  F1("cosf", cosf(x), -100, 100)
  F1("sinf", sinf(x), -100, 100)
  F1("sqrtf", sqrtf(x), 0, 100)
  D1("exp", exp(x), -60, 5)
  D1("sin", sin(x), -100, 100)
  D1("cos", cos(x), -100, 100)
  D2("pow", pow(x+1.5,y), -1, 3)
  D1("tanh", tanh(x), -20, 20)
  D1("atan", atan(x), -10, 10)
  D2("hypot", hypot(x,y), -10, 10)
  D1("erfc", erfc(x), -6, 6)
  D1("acos", acos(x), -1, 1)
  D1("asin", asin(x), -1, 1)
  D1("log", log(x), 0, 100)
  return 0;
}
