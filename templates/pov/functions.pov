{{constants}}
// ---- Terms (one function per term of the model catalog)
{{terms}}// ---- Shading frame: unit n, l, v → Reflectance's inputs
{{frames}}
