//! CPU pipeline: GL 1.2 texturing, rasterizer, blending, NV_register_combiners, techniques.
