function F = piston_force(t, qi, qdi)
% Gas force on the piston of tests/adm/mfile/Models/piston.adm, written
% for camlink's tests in the shape of the course's pistonForce.m: a
% pressure that falls as the piston moves out (x' > 0), a sinusoidal
% release near the end of the stroke, none on the return.
x = qi(1);    % piston position (m)
v = qdi(1);   % piston speed (m/s)

F = [0;0];
if v > 0
    if x > 4.5
        F(1) = 0;
    elseif x > 4
        F(1) = -2500 * ( 1 - sin(2*pi*(x-4.25)) );
    elseif x >= 1.5
        F(1) = 2000 - 7000/(5-x);
    else
        F(1) = 0;
    end
end
%{
A side load on the guide, proportional to the gas force, with
the piston's angle and rate read as well.
%}
side = 0.01 * F(1) * cos(qi(3)) ...  continued
    + 2*qdi(3) - 0*qi(2)^2;
if ~(t < 0.05) && abs(v) ~= 0 || t == 1e9
    F(2) = side;
elseif t <= 0.01
    F(2) = -side^2 / 1e4 + sqrt(exp(log(1 + t))) - 1 + tan(0*qdi(2));
end
end
