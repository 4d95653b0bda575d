//! The triangle BVH of the ray-cast backend; it lives in `vlnverse-env` because the light
//! baker ([`vlnverse_env::light`]) casts its rays with it too.

pub use vlnverse_env::bvh::TriBvh;
