// Mathematical constants and float limits shared by every shader.
const PI: f32 = 3.14159265358979;
const TWO_PI: f32 = 6.28318530717959;
const INV_PI: f32 = 0.318309886183791;
// Smallest positive normal f32: guards denominators (max(den, FLT_MIN)) without changing
// any value that is representable as a normal number.
const FLT_MIN: f32 = 1.17549435e-38;
// Largest finite f32: results are clamped to it so nothing overflows to Inf.
const FLT_MAX: f32 = 3.40282347e38;
