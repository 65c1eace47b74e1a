// Rule: frames in a cycle (heading <- disk <- lean <- heading). Error at `disk` in `heading = rotate(disk, z, psi)`.
chaplygin_macros::model! {
    pub struct RollingDisk {
        coordinates: [x, y, psi, phi, theta],
        parameters: [m = 1.0, r = 0.5, g = 9.81],
        frames: [
            heading = rotate(disk, z, psi),
            lean = rotate(heading, x, phi),
            disk = rotate(lean, y, theta),
        ],
        points: [
            contact = origin + x*ground.x + y*ground.y,
            center = contact + r*lean.z,
        ],
        bodies: [wheel = body(disk, center, m, diag(m*r^2/4, m*r^2/2, m*r^2/4))],
        gravity: -g*ground.z,
        no_slip: [rolling = no_slip(wheel, contact, [ground.x, ground.y])],
    }
}

fn main() {}
