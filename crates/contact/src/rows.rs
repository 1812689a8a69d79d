//! Where a contact's rows go: the solver bodies they are built against, read, beside the rows,
//! blocks and biases they are appended to, written.
//!
//! A [`Problem`] lends its own ([`ContactRows::of`]). Keeping the two apart lets a caller build
//! many contacts at once: each thread appends to rows, blocks and biases of its own beside the
//! one list of bodies, and the pieces are joined in order afterwards, each block's row range
//! moved by the rows before it ([`ContactRows::append`]). A contact's rows depend on nothing
//! but the contact, the bodies and the settings, so the joined problem is the one built in a
//! single pass, to the bit.

use tatami_lcp::{Block, Problem, Row, SolverBody};

use crate::ContactProjection;

/// The bodies a contact's rows read, and the rows, blocks and position-pass biases (one per
/// row, see [`ContactModel::build_split`](crate::ContactModel::build_split)) they are appended
/// to. A block's row range counts from the start of `rows`.
#[derive(Debug)]
pub struct ContactRows<'a> {
    /// Every body a contact may name, as the solver will see them.
    pub bodies: &'a [SolverBody],
    /// The rows built so far.
    pub rows: &'a mut Vec<Row>,
    /// The blocks built so far, each over a range of `rows`.
    pub blocks: &'a mut Vec<Block<ContactProjection>>,
    /// One bias per row of `rows`.
    pub biases: &'a mut Vec<f64>,
}

impl<'a> ContactRows<'a> {
    /// `problem`'s bodies, rows and blocks, with `biases` beside its rows.
    pub fn of(problem: &'a mut Problem<ContactProjection>, biases: &'a mut Vec<f64>) -> Self {
        Self {
            bodies: &problem.bodies,
            rows: &mut problem.rows,
            blocks: &mut problem.blocks,
            biases,
        }
    }

    /// Moves the rows, blocks and biases of `piece` (built apart against the same bodies) to
    /// the end of these, each of its blocks' row ranges moved past the rows already here;
    /// `piece` is left empty, its storage kept for reuse.
    ///
    /// ```
    /// use nalgebra::{Point2, Point3, Vector3};
    /// use tatami_contact::{
    ///     Contact, ContactFrame, ContactModel, ContactRows, ContactSettings, Material,
    /// };
    /// use tatami_geometry::ConvexPolygon;
    /// use tatami_lcp::{BodyId, Problem, SolverBody};
    ///
    /// let mut cube = SolverBody::fixed();
    /// cube.inv_mass = 1.0;
    /// let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    /// let square = square.map(|(x, y)| Point2::new(x, y));
    /// let contact = Contact {
    ///     body_a: BodyId(0),
    ///     body_b: BodyId(1),
    ///     centre_a: Point3::new(0.0, 0.0, 1.0),
    ///     centre_b: Point3::new(0.0, 0.0, -1.0),
    ///     frame: ContactFrame::from_normal(Point3::origin(), Vector3::z())?,
    ///     support: ConvexPolygon::from_points(&square)?,
    ///     depths: vec![0.001; 4],
    ///     material: Material::new(0.5, 0.5, 0.0)?,
    ///     landing: Vec::new(),
    ///     bounce_speed: 0.0,
    /// };
    /// let (model, settings) = (ContactModel::Vertex, ContactSettings::default());
    /// let bodies = vec![cube, SolverBody::fixed()];
    ///
    /// // Two contacts built in one pass...
    /// let mut whole = Problem { bodies: bodies.clone(), ..Default::default() };
    /// let mut whole_biases = Vec::new();
    /// for _ in 0..2 {
    ///     model.build_split(&contact, 0.01, &settings, &mut whole, &mut whole_biases)?;
    /// }
    /// // ...and the second built apart, then joined to the first.
    /// let mut joined = Problem { bodies: bodies.clone(), ..Default::default() };
    /// let mut biases = Vec::new();
    /// model.build_split(&contact, 0.01, &settings, &mut joined, &mut biases)?;
    /// let (mut rows, mut blocks, mut piece_biases) = (Vec::new(), Vec::new(), Vec::new());
    /// let mut piece = ContactRows {
    ///     bodies: &bodies,
    ///     rows: &mut rows,
    ///     blocks: &mut blocks,
    ///     biases: &mut piece_biases,
    /// };
    /// model.build_rows(&contact, None, 0.01, &settings, &mut piece)?;
    /// ContactRows::of(&mut joined, &mut biases).append(piece);
    ///
    /// assert_eq!(joined.rows, whole.rows);
    /// assert_eq!(joined.blocks, whole.blocks);
    /// assert_eq!(biases, whole_biases);
    /// assert_eq!(joined.blocks[4].rows, 12..15, "the second contact's first block, moved");
    /// assert!(rows.is_empty() && blocks.is_empty() && piece_biases.is_empty(), "moved out");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn append(&mut self, piece: ContactRows<'_>) {
        let offset = self.rows.len();
        self.rows.append(piece.rows);
        self.biases.append(piece.biases);
        self.blocks.extend(piece.blocks.drain(..).map(|mut block| {
            block.rows = block.rows.start + offset..block.rows.end + offset;
            block
        }));
    }
}
