use geom::slice::PlaneFrame;
use nalgebra::Vector3;
use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};

/// A vector as `[x, y, z]`.
pub(crate) fn vec3<S: Serializer>(v: &Vector3<f64>, s: S) -> Result<S::Ok, S::Error> {
    [v.x, v.y, v.z].serialize(s)
}

/// A plane frame as `{"normal", "u", "v"}`.
pub(crate) fn frame<S: Serializer>(f: &PlaneFrame, s: S) -> Result<S::Ok, S::Error> {
    let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
    let mut st = s.serialize_struct("PlaneFrame", 3)?;
    st.serialize_field("normal", &arr(&f.normal))?;
    st.serialize_field("u", &arr(&f.u))?;
    st.serialize_field("v", &arr(&f.v))?;
    st.end()
}
