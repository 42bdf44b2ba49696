//! Axis-aligned and oriented boxes.
//!
//! Entry points: [`Aabb`](crate::bbox::Aabb), [`Obb`](crate::bbox::Obb). A block in a job is an [`Obb`](crate::bbox::Obb): centre, rotation (unit
//! quaternion) and size.

use nalgebra::{UnitQuaternion, Vector3};

use crate::error::{GeomError, Result};

/// An axis-aligned box `[min, max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vector3<f64>,
    /// Largest corner.
    pub max: Vector3<f64>,
}

impl Aabb {
    /// The smallest box containing the points; `None` for no points.
    pub fn from_points(points: &[Vector3<f64>]) -> Option<Self> {
        let first = points.first()?;
        let mut b = Self {
            min: *first,
            max: *first,
        };
        for p in points {
            b.min = b.min.inf(p);
            b.max = b.max.sup(p);
        }
        Some(b)
    }

    /// Edge lengths.
    pub fn size(&self) -> Vector3<f64> {
        self.max - self.min
    }

    /// Centre point.
    pub fn center(&self) -> Vector3<f64> {
        0.5 * (self.min + self.max)
    }

    /// Whether `p` lies inside or on the box.
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        (0..3).all(|i| p[i] >= self.min[i] && p[i] <= self.max[i])
    }

    /// Whether the boxes overlap (touching counts).
    pub fn intersects(&self, o: &Aabb) -> bool {
        (0..3).all(|i| self.min[i] <= o.max[i] && o.min[i] <= self.max[i])
    }

    /// The box grown by `margin` on every side.
    pub fn inflate(&self, margin: f64) -> Self {
        let m = Vector3::repeat(margin);
        Self {
            min: self.min - m,
            max: self.max + m,
        }
    }

    /// The eight corners.
    pub fn corners(&self) -> [Vector3<f64>; 8] {
        std::array::from_fn(|i| {
            Vector3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// Range of `dir · p` over the box.
    pub fn project(&self, dir: &Vector3<f64>) -> (f64, f64) {
        let c = self.corners();
        c.iter()
            .map(|p| dir.dot(p))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    }
}

/// An oriented box: centre, rotation and full edge lengths along its local axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    /// Centre.
    pub center: Vector3<f64>,
    /// Rotation from box-local to world coordinates.
    pub rotation: UnitQuaternion<f64>,
    /// Edge lengths along the local x, y, z axes.
    pub size: Vector3<f64>,
}

impl Obb {
    /// A box with positive, finite size.
    ///
    /// # Errors
    /// [`GeomError::InvalidDomain`] for a non-positive size, [`GeomError::NonFinite`] for NaN.
    pub fn try_new(
        center: Vector3<f64>,
        rotation: UnitQuaternion<f64>,
        size: Vector3<f64>,
    ) -> Result<Self> {
        if center
            .iter()
            .chain(size.iter())
            .chain(rotation.coords.iter())
            .any(|v| !v.is_finite())
        {
            return Err(GeomError::NonFinite {
                what: "box centre, rotation or size".into(),
            });
        }
        if size.iter().any(|&s| s <= 0.0) {
            return Err(GeomError::InvalidDomain(format!(
                "box size must be positive, got ({}, {}, {})",
                size.x, size.y, size.z
            )));
        }
        Ok(Self {
            center,
            rotation,
            size,
        })
    }

    /// An axis-aligned box as an [`Obb`].
    pub fn from_aabb(b: &Aabb) -> Self {
        Self {
            center: b.center(),
            rotation: UnitQuaternion::identity(),
            size: b.size(),
        }
    }

    /// World point to box-local coordinates (origin at the centre).
    pub fn to_local(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.inverse_transform_vector(&(p - self.center))
    }

    /// Whether `p` lies inside or on the box.
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        let l = self.to_local(p);
        (0..3).all(|i| l[i].abs() <= 0.5 * self.size[i])
    }

    /// The eight corners in world coordinates.
    pub fn corners(&self) -> [Vector3<f64>; 8] {
        std::array::from_fn(|i| {
            let l = Vector3::new(
                if i & 1 == 0 { -0.5 } else { 0.5 },
                if i & 2 == 0 { -0.5 } else { 0.5 },
                if i & 4 == 0 { -0.5 } else { 0.5 },
            )
            .component_mul(&self.size);
            self.center + self.rotation * l
        })
    }

    /// Volume.
    pub fn volume(&self) -> f64 {
        self.size.x * self.size.y * self.size.z
    }

    /// The axis-aligned box around it.
    pub fn aabb(&self) -> Aabb {
        let c = self.corners();
        Aabb::from_points(&c).unwrap_or(Aabb {
            min: self.center,
            max: self.center,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_box_contains_and_bounds() {
        let r = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_4);
        let b = Obb::try_new(Vector3::new(1.0, 1.0, 0.0), r, Vector3::new(2.0, 2.0, 2.0)).unwrap();
        assert!(b.contains(&Vector3::new(1.0, 2.4, 0.0)));
        assert!(!b.contains(&Vector3::new(2.0, 2.0, 0.0)));
        let a = b.aabb();
        assert!((a.size().x - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert!((b.volume() - 8.0).abs() < 1e-12);
        assert!(Obb::try_new(Vector3::zeros(), r, Vector3::new(1.0, -1.0, 1.0)).is_err());
    }

    #[test]
    fn aabb_basics() {
        let a = Aabb::from_points(&[Vector3::new(0.0, 1.0, 2.0), Vector3::new(3.0, -1.0, 2.5)])
            .unwrap();
        assert_eq!(a.size(), Vector3::new(3.0, 2.0, 0.5));
        assert!(a.contains(&Vector3::new(1.0, 0.0, 2.2)));
        assert_eq!(a.project(&Vector3::x()), (0.0, 3.0));
        assert!(a.intersects(&a.inflate(1.0)));
    }
}
