//! The bicycle's topology, written once: the four bodies, the joint tree that connects them
//! (rear frame at the root; rear wheel, front frame and front wheel below it), the nine tree
//! speeds with their named offsets, which of them move each body, and the layout of the
//! constraint rows.
//!
//! ```text
//!            rear frame B (root: ν, ω_B = tree speeds 0..6)
//!           /             \
//!   rear hub (σ_R, 7)    steer (δ̇, 6)
//!         |                 |
//!   rear wheel R       front frame H
//!                           |
//!                     front hub (σ_F, 8)
//!                           |
//!                      front wheel F
//! ```
//!
//! Row layout: the holonomic rows are the three joints' five rows each (in [`JOINTS`] order),
//! then the two contact heights; the velocity rows are those differentiated, then each
//! contact's longitudinal and lateral rolling rows. Everything that builds, assembles or reads
//! rows ([`super::Model::new`], the position chain, the tree map, the projection, the dense
//! reference) takes its indices from here.

/// Index of the rear wheel R among the bodies.
pub const REAR_WHEEL: usize = 0;
/// Index of the rear frame B (frame and rider).
pub const REAR_FRAME: usize = 1;
/// Index of the front frame H (fork and handlebar).
pub(crate) const FRONT_FRAME: usize = 2;
/// Index of the front wheel F.
pub const FRONT_WHEEL: usize = 3;
/// Number of bodies.
pub(crate) const BODIES: usize = 4;
/// Body names in index order.
pub const BODY_NAMES: [&str; BODIES] = ["rear wheel", "rear frame", "front frame", "front wheel"];

/// The root of the joint tree: its six speeds (hub velocity ν and angular velocity ω_B) are the
/// first six tree speeds.
pub(crate) const ROOT: usize = REAR_FRAME;

/// Number of tree speeds w = [ν, ω_B, δ̇, σ_R, σ_F].
pub(crate) const TREE: usize = 9;
/// Offset of ν, the rear hub's velocity in rear frame axes (3 speeds).
pub(crate) const HUB_VELOCITY: usize = 0;
/// Offset of ω_B, the rear frame's angular velocity in its own axes (3 speeds).
pub(crate) const FRAME_RATE: usize = 3;
/// Offset of δ̇, the steer rate.
pub(crate) const TREE_STEER_RATE: usize = 6;
/// Offset of σ_R, the rear wheel's spin rate relative to the rear frame.
pub(crate) const REAR_SPIN: usize = 7;
/// Offset of σ_F, the front wheel's spin rate relative to the front frame.
pub(crate) const FRONT_SPIN: usize = 8;

/// Number of tree speeds once a rolling rear wheel's rows are solved for ν:
/// w' = [ω_B, δ̇, σ_R, σ_F].
pub(crate) const ROLLING_TREE: usize = TREE - 3;

/// The index in w' of a tree speed other than ν.
pub(crate) const fn rolling(tree_speed: usize) -> usize {
    assert!(tree_speed >= FRAME_RATE && tree_speed < TREE);
    tree_speed - FRAME_RATE
}

/// What a joint is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum JointKind {
    /// A wheel's axle: the wheel turns about its own y axis (the hub).
    Hub,
    /// The steer axis between the rear and the front frame.
    Steer,
}

/// One joint of the tree: the bodies it joins and the tree speed that turns the child.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct JointSpec {
    /// The body nearer the root.
    pub parent: usize,
    /// The body it carries.
    pub child: usize,
    /// Hub or steer.
    pub kind: JointKind,
    /// The tree speed of the child relative to the parent.
    pub speed: usize,
}

/// Index of the rear hub joint (B–R) among the joints.
pub(crate) const REAR_HUB: usize = 0;
/// Index of the steer joint (B–H).
pub(crate) const STEER_JOINT: usize = 1;
/// Index of the front hub joint (H–F).
pub(crate) const FRONT_HUB: usize = 2;
/// Number of joints.
pub(crate) const JOINT_COUNT: usize = 3;

/// The joints, in row order.
pub(crate) const JOINTS: [JointSpec; JOINT_COUNT] = [
    JointSpec {
        parent: REAR_FRAME,
        child: REAR_WHEEL,
        kind: JointKind::Hub,
        speed: REAR_SPIN,
    },
    JointSpec {
        parent: REAR_FRAME,
        child: FRONT_FRAME,
        kind: JointKind::Steer,
        speed: TREE_STEER_RATE,
    },
    JointSpec {
        parent: FRONT_FRAME,
        child: FRONT_WHEEL,
        kind: JointKind::Hub,
        speed: FRONT_SPIN,
    },
];

/// One wheel–ground contact: the wheel and the frame that carries its axle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ContactSpec {
    /// The wheel's body index.
    pub wheel: usize,
    /// The frame carrying the wheel (the parent of its hub joint).
    pub frame: usize,
}

/// Index of the rear contact among the contacts.
pub(crate) const REAR_CONTACT: usize = 0;
/// Index of the front contact.
pub(crate) const FRONT_CONTACT: usize = 1;
/// Number of contacts.
pub(crate) const CONTACT_COUNT: usize = 2;

/// The contacts, in row order.
pub(crate) const CONTACTS: [ContactSpec; CONTACT_COUNT] = [
    ContactSpec {
        wheel: REAR_WHEEL,
        frame: parent(REAR_WHEEL),
    },
    ContactSpec {
        wheel: FRONT_WHEEL,
        frame: parent(FRONT_WHEEL),
    },
];

/// The parent of a body other than the root.
const fn parent(body: usize) -> usize {
    let mut j = 0;
    while j < JOINT_COUNT {
        if JOINTS[j].child == body {
            return JOINTS[j].parent;
        }
        j += 1;
    }
    panic!("the root has no parent");
}

/// Rows per joint: point coincidence (3) and axis alignment (2).
pub(crate) const JOINT_ROWS: usize = 5;
/// Holonomic rows: the joints' rows, then one contact height per contact.
pub(crate) const HOLONOMIC_ROWS: usize = JOINT_ROWS * JOINT_COUNT + CONTACT_COUNT;
/// All velocity rows: the holonomic ones differentiated, then two rolling (non-holonomic)
/// rows per contact.
pub(crate) const VELOCITY_ROWS: usize = HOLONOMIC_ROWS + 2 * CONTACT_COUNT;

/// First row of a joint.
pub(crate) const fn joint_row(joint: usize) -> usize {
    JOINT_ROWS * joint
}

/// The height (holonomic) row of a contact.
pub(crate) const fn height_row(contact: usize) -> usize {
    JOINT_ROWS * JOINT_COUNT + contact
}

/// The longitudinal rolling row of a contact (its spin lock for a skate).
pub(crate) const fn longitudinal_row(contact: usize) -> usize {
    HOLONOMIC_ROWS + 2 * contact
}

/// The lateral rolling row of a contact.
pub(crate) const fn lateral_row(contact: usize) -> usize {
    HOLONOMIC_ROWS + 2 * contact + 1
}

/// The bodies a holonomic row touches, in ascending index order (a contact height touches its
/// wheel only, given twice).
pub(crate) const fn row_bodies(row: usize) -> [usize; 2] {
    if row < JOINT_ROWS * JOINT_COUNT {
        let joint = JOINTS[row / JOINT_ROWS];
        if joint.parent < joint.child {
            [joint.parent, joint.child]
        } else {
            [joint.child, joint.parent]
        }
    } else {
        let wheel = CONTACTS[row - JOINT_ROWS * JOINT_COUNT].wheel;
        [wheel, wheel]
    }
}

/// Number of joints between a body and the root.
const fn depth(body: usize) -> usize {
    let mut n = 0;
    let mut k = body;
    while k != ROOT {
        k = parent(k);
        n += 1;
    }
    n
}

/// The tree speed of the joint above a body other than the root.
const fn joint_speed(body: usize) -> usize {
    let mut j = 0;
    while j < JOINT_COUNT {
        if JOINTS[j].child == body {
            return JOINTS[j].speed;
        }
        j += 1;
    }
    panic!("the root has no joint above it");
}

/// Sorts a small array in place (insertion sort, usable in constants).
const fn sorted<const C: usize>(mut a: [usize; C]) -> [usize; C] {
    let mut i = 1;
    while i < C {
        let mut j = i;
        while j > 0 && a[j - 1] > a[j] {
            let t = a[j - 1];
            a[j - 1] = a[j];
            a[j] = t;
            j -= 1;
        }
        i += 1;
    }
    a
}

/// The tree speeds that can move a body (the other columns of its J are zero): the root's six
/// and the joint speeds on its path to the root, ascending.
const fn tree_columns<const C: usize>(body: usize) -> [usize; C] {
    assert!(C == 6 + depth(body));
    let mut out = [0; C];
    let mut n = 0;
    while n < 6 {
        out[n] = n;
        n += 1;
    }
    let mut k = body;
    while k != ROOT {
        out[n] = joint_speed(k);
        n += 1;
        k = parent(k);
    }
    sorted(out)
}

/// Whether a tree speed lies on the path from `body` to the root.
const fn on_path(body: usize, speed: usize) -> bool {
    let mut k = body;
    while k != ROOT {
        if joint_speed(k) == speed {
            return true;
        }
        k = parent(k);
    }
    false
}

/// Number of rolling-tree columns that can move a body: ω_B, the joint speeds on its path and
/// those on the rear wheel's path (ν, eliminated, depends on them), each once.
const fn rolling_count(body: usize) -> usize {
    let mut n = 3 + depth(body);
    let mut k = CONTACTS[REAR_CONTACT].wheel;
    while k != ROOT {
        if !on_path(body, joint_speed(k)) {
            n += 1;
        }
        k = parent(k);
    }
    n
}

/// The columns of w' = [ω_B, δ̇, σ_R, σ_F] that can move a body once a rolling rear wheel's
/// rows are solved for ν, ascending.
const fn rolling_columns<const C: usize>(body: usize) -> [usize; C] {
    assert!(C == rolling_count(body));
    let mut out = [0; C];
    let mut n = 0;
    while n < 3 {
        out[n] = n;
        n += 1;
    }
    let mut k = body;
    while k != ROOT {
        out[n] = rolling(joint_speed(k));
        n += 1;
        k = parent(k);
    }
    let mut k = CONTACTS[REAR_CONTACT].wheel;
    while k != ROOT {
        if !on_path(body, joint_speed(k)) {
            out[n] = rolling(joint_speed(k));
            n += 1;
        }
        k = parent(k);
    }
    sorted(out)
}

/// [`tree_columns`] of each body.
pub(crate) const REAR_WHEEL_COLUMNS: [usize; 6 + depth(REAR_WHEEL)] = tree_columns(REAR_WHEEL);
/// See [`REAR_WHEEL_COLUMNS`].
pub(crate) const REAR_FRAME_COLUMNS: [usize; 6 + depth(REAR_FRAME)] = tree_columns(REAR_FRAME);
/// See [`REAR_WHEEL_COLUMNS`].
pub(crate) const FRONT_FRAME_COLUMNS: [usize; 6 + depth(FRONT_FRAME)] = tree_columns(FRONT_FRAME);
/// See [`REAR_WHEEL_COLUMNS`].
pub(crate) const FRONT_WHEEL_COLUMNS: [usize; 6 + depth(FRONT_WHEEL)] = tree_columns(FRONT_WHEEL);
/// [`rolling_columns`] of each body.
pub(crate) const REAR_WHEEL_ROLLING: [usize; rolling_count(REAR_WHEEL)] =
    rolling_columns(REAR_WHEEL);
/// See [`REAR_WHEEL_ROLLING`].
pub(crate) const REAR_FRAME_ROLLING: [usize; rolling_count(REAR_FRAME)] =
    rolling_columns(REAR_FRAME);
/// See [`REAR_WHEEL_ROLLING`].
pub(crate) const FRONT_FRAME_ROLLING: [usize; rolling_count(FRONT_FRAME)] =
    rolling_columns(FRONT_FRAME);
/// See [`REAR_WHEEL_ROLLING`].
pub(crate) const FRONT_WHEEL_ROLLING: [usize; rolling_count(FRONT_WHEEL)] =
    rolling_columns(FRONT_WHEEL);

#[cfg(test)]
mod tests {
    use super::*;

    /// The layout the rest of the model was written against.
    #[test]
    fn layout() {
        assert_eq!((HOLONOMIC_ROWS, VELOCITY_ROWS), (17, 21));
        assert_eq!(
            [
                height_row(0),
                height_row(1),
                longitudinal_row(1),
                lateral_row(1)
            ],
            [15, 16, 19, 20]
        );
        assert_eq!(REAR_WHEEL_COLUMNS, [0, 1, 2, 3, 4, 5, 7]);
        assert_eq!(REAR_FRAME_COLUMNS, [0, 1, 2, 3, 4, 5]);
        assert_eq!(FRONT_FRAME_COLUMNS, [0, 1, 2, 3, 4, 5, 6]);
        assert_eq!(FRONT_WHEEL_COLUMNS, [0, 1, 2, 3, 4, 5, 6, 8]);
        assert_eq!(REAR_WHEEL_ROLLING, [0, 1, 2, 4]);
        assert_eq!(REAR_FRAME_ROLLING, [0, 1, 2, 4]);
        assert_eq!(FRONT_FRAME_ROLLING, [0, 1, 2, 3, 4]);
        assert_eq!(FRONT_WHEEL_ROLLING, [0, 1, 2, 3, 4, 5]);
        assert_eq!(row_bodies(2), [REAR_WHEEL, REAR_FRAME]);
        assert_eq!(row_bodies(7), [REAR_FRAME, FRONT_FRAME]);
        assert_eq!(row_bodies(16), [FRONT_WHEEL, FRONT_WHEEL]);
        assert_eq!(CONTACTS[FRONT_CONTACT].frame, FRONT_FRAME);
    }
}
